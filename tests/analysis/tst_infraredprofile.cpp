// Infrared frames decode to the right temperatures and the axial screw profile matches a
// synthetic truth away from the nut, which is masked.

#include "InfraredFrame.h"
#include "InfraredProfileExtractor.h"

#include "../support/InfraredLine.h"

#include <QTemporaryDir>
#include <QtTest>

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <fstream>

using namespace driftlab;

namespace {
double truthProfile(double x_m) { return 21.0 + 6.0 * std::exp(-x_m / 0.25) + 2.0 * x_m; }

// A 320x120 frame: background at 18 degC, the screw a band along a slightly tilted line,
// the nut housing a hot block (45 degC) over [nutCentre +- 0.106 m].
InfraredCalibration makeCalibration()
{
    return testinfrared::screwLine(20.0, 50.0, 300.0, 70.0, 7.0, 0.0, 0.8);
}

cv::Mat makeCounts(const InfraredCalibration &c, double nutCentre_m)
{
    cv::Mat counts(120, 320, CV_16UC1);
    const double dx = c.lineX1_px - c.lineX0_px, dy = c.lineY1_px - c.lineY0_px;
    const double len2 = dx * dx + dy * dy;
    for (int y = 0; y < counts.rows; ++y) {
        for (int x = 0; x < counts.cols; ++x) {
            // Project the pixel on the axis line.
            const double f = ((x - c.lineX0_px) * dx + (y - c.lineY0_px) * dy) / len2;
            const double dist = std::fabs((x - c.lineX0_px) * dy - (y - c.lineY0_px) * dx) / std::sqrt(len2);
            const double s = c.line0_m + f * (c.line1_m - c.line0_m);
            double t = 18.0;
            if (f >= -0.01 && f <= 1.01 && dist <= 6.0)
                t = truthProfile(s);
            if (std::fabs(s - nutCentre_m) <= 0.106 && dist <= 20.0)
                t = 45.0;
            counts.at<quint16>(y, x) = static_cast<quint16>(std::lround((t + 273.15) / 0.01));
        }
    }
    return counts;
}
} // namespace

class TestInfraredProfile : public QObject {
    Q_OBJECT
private slots:
    void pngRoundTripAndProfile();
    void radiometricCsv();
    void rejectsBadFiles();
};

void TestInfraredProfile::pngRoundTripAndProfile()
{
    QTemporaryDir dir;
    const InfraredCalibration cal = makeCalibration();
    const double nut = 0.45;
    const cv::Mat counts = makeCounts(cal, nut);
    for (const char *ext : {"png", "tif"}) {
        const std::string path = dir.filePath(QStringLiteral("frame.") + QLatin1String(ext)).toStdString();
        QVERIFY(cv::imwrite(path, counts));
        const cv::Mat t = InfraredFrame::readTemperature(path, cal);
        QCOMPARE(t.type(), CV_32FC1);
        QVERIFY(std::fabs(t.at<float>(0, 0) - 18.0f) < 0.006f); // lossless: 0.01 K counts
        const auto profile = InfraredProfileExtractor(cal).extract(t, 81, nut, 0.212);
        int valid = 0;
        for (const ProfilePoint &p : profile) {
            if (std::fabs(p.x_m - nut) <= 0.106 + 0.01) {
                QVERIFY2(!p.valid, "a point under the nut housing was not masked");
                continue;
            }
            QVERIFY(p.valid);
            ++valid;
            // Pixels across the band sample the same axial station to within the tilt:
            // +-3 px across a 281 px line is < 1e-3 m, the profile slope < 30 K/m.
            QVERIFY2(std::fabs(p.temperature_C - truthProfile(p.x_m)) < 0.06,
                     qPrintable(QStringLiteral("x=%1 got %2 want %3").arg(p.x_m).arg(p.temperature_C).arg(truthProfile(p.x_m))));
        }
        QVERIFY(valid >= 55);
    }
}

void TestInfraredProfile::radiometricCsv()
{
    QTemporaryDir dir;
    const std::string path = dir.filePath(QStringLiteral("frame.csv")).toStdString();
    std::ofstream(path) << "20.5;21,25;22\n23;24;25.75\n";
    const cv::Mat t = InfraredFrame::readTemperature(path, InfraredCalibration());
    QCOMPARE(t.rows, 2);
    QCOMPARE(t.cols, 3);
    QCOMPARE(t.at<float>(0, 1), 21.25f); // decimal comma accepted with ';' separators
    QCOMPARE(t.at<float>(1, 2), 25.75f);
}

void TestInfraredProfile::rejectsBadFiles()
{
    QTemporaryDir dir;
    const std::string csv = dir.filePath(QStringLiteral("bad.csv")).toStdString();
    std::ofstream(csv) << "20,21\n22,warm\n";
    try {
        InfraredFrame::readTemperature(csv, InfraredCalibration());
        QFAIL("a non-numeric cell was accepted");
    } catch (const std::runtime_error &e) {
        QVERIFY2(QString::fromStdString(e.what()).contains(QStringLiteral("line 2, column 2")), e.what());
    }
    const std::string ragged = dir.filePath(QStringLiteral("ragged.csv")).toStdString();
    std::ofstream(ragged) << "20,21\n22\n";
    QVERIFY_EXCEPTION_THROWN(InfraredFrame::readTemperature(ragged, InfraredCalibration()), std::runtime_error);
    const std::string eight = dir.filePath(QStringLiteral("eight.png")).toStdString();
    cv::imwrite(eight, cv::Mat(4, 4, CV_8UC1, cv::Scalar(7)));
    try {
        InfraredFrame::readTemperature(eight, InfraredCalibration());
        QFAIL("an 8-bit frame was accepted");
    } catch (const std::runtime_error &e) {
        QVERIFY(QString::fromStdString(e.what()).contains(QStringLiteral("16-bit")));
    }
    const std::string broken = dir.filePath(QStringLiteral("broken.png")).toStdString();
    std::ofstream(broken) << "\x89PNG\r\n\x1a\n garbage";
    QVERIFY_EXCEPTION_THROWN(InfraredFrame::readTemperature(broken, InfraredCalibration()), std::runtime_error);
}

QTEST_APPLESS_MAIN(TestInfraredProfile)
#include "tst_infraredprofile.moc"
