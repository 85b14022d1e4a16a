// Infrared cameras: the calibration and its manifest block, the frame conversion path a
// UVC Y16 stream and camera software exports take (16-bit counts, undecoded Y16 bytes,
// float temperatures, CSV; 8-bit refused), the watched folder with frames written during
// the test (TIFF, PNG, CSV, a file still being written, a corrupt one), and the UVC
// device's configuration and missing-camera error. No camera is attached here: streaming
// from a real UVC core is not tested.
#include "InfraredCalibration.h"
#include "InfraredFolderDevice.h"
#include "InfraredFrameConverter.h"
#include "SessionClock.h"
#include "UvcCameraDevice.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QTemporaryDir>
#include <QtTest>

#include <opencv2/imgcodecs.hpp>

using namespace driftlab;

namespace {
QJsonObject json(const QString &text)
{
    return QJsonDocument::fromJson(text.toUtf8()).object();
}

InfraredCalibration calibration(const char *text)
{
    JsonFields f(json(QString::fromLatin1(text)), QStringLiteral("calibration"));
    return InfraredCalibration::fromJson(f);
}

void writeFile(const QString &path, const QByteArray &data)
{
    QFile f(path);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(data);
}
} // namespace

class TestInfrared : public QObject {
    Q_OBJECT
private slots:
    void calibrationAndManifest();
    void conversionPath();
    void csvFrames();
    void folderWrittenDuringTheTest();
    void uvcConfigurationAndMissingCamera();
};

void TestInfrared::calibrationAndManifest()
{
    const InfraredCalibration c = calibration(R"({"scale":0.04,"offset":-273.15,"emissivity":0.95,"note":"black tape",
        "screw_line_px":[40,256,600,256],"screw_line_m":[0,0.8],"screw_width_px":12})");
    QCOMPARE(c.count(26.85), static_cast<quint16>(7500)); // (26.85 + 273.15) / 0.04
    QCOMPARE(c.count(std::nan("")), static_cast<quint16>(0));
    QCOMPARE(c.count(1e9), static_cast<quint16>(65535));
    const QJsonObject m = c.manifest(QStringLiteral("cam1"));
    QCOMPARE(m.value(QStringLiteral("scale")).toDouble(), 0.04);
    QCOMPARE(m.value(QStringLiteral("offset")).toDouble(), -273.15);
    QCOMPARE(m.value(QStringLiteral("emissivity")).toDouble(), 0.95);
    QCOMPARE(m.value(QStringLiteral("screw_line_px")).toArray().at(1).toArray().at(0).toDouble(), 600.0);
    QCOMPARE(m.value(QStringLiteral("screw_line_m")).toArray().at(1).toDouble(), 0.8);
    QCOMPARE(m.value(QStringLiteral("screw_width_px")).toInt(), 12);
    try {
        calibration(R"({"screw_line_px":[1,2,3,4]})");
        QFAIL("a screw line without its metres accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).startsWith(QLatin1String("calibration.screw_line_m: give")), e.what());
    }
    QVERIFY_EXCEPTION_THROWN(calibration(R"({"emissivity":1.5})"), std::invalid_argument);
}

void TestInfrared::conversionPath()
{
    const InfraredCalibration c; // centi-kelvin
    // 16-bit counts (Y16 decoded by OpenCV, 16-bit TIFF/PNG): kept as they are.
    cv::Mat counts(3, 4, CV_16UC1);
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 4; ++k)
            counts.at<quint16>(r, k) = static_cast<quint16>(29315 + 100 * r + k);
    IrFrame f = InfraredFrameConverter::toFrame(counts, c, QStringLiteral("y16"));
    QCOMPARE(f.width, 4);
    QCOMPARE(f.height, 3);
    QCOMPARE(f.pixels[2 * 4 + 3], static_cast<quint16>(29518));
    // Undecoded Y16 (CAP_PROP_CONVERT_RGB off): two bytes per pixel, little-endian, as a
    // 2-channel image or as one row of raw bytes.
    cv::Mat y16(3, 4, CV_8UC2);
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 4; ++k) {
            y16.at<cv::Vec2b>(r, k)[0] = static_cast<uchar>(counts.at<quint16>(r, k) & 0xff);
            y16.at<cv::Vec2b>(r, k)[1] = static_cast<uchar>(counts.at<quint16>(r, k) >> 8);
        }
    QCOMPARE(InfraredFrameConverter::toFrame(y16, c, QStringLiteral("yuyv")).pixels, f.pixels);
    cv::Mat raw(1, 24, CV_8UC1, y16.data);
    QCOMPARE(InfraredFrameConverter::toFrame(raw, c, QStringLiteral("raw"), 4, 3).pixels, f.pixels);
    // Temperatures (float TIFF, CSV) through the calibration.
    cv::Mat celsius(2, 2, CV_32FC1);
    celsius.at<float>(0, 0) = 20.0f;
    celsius.at<float>(0, 1) = 35.5f;
    celsius.at<float>(1, 0) = -5.0f;
    celsius.at<float>(1, 1) = 100.25f;
    f = InfraredFrameConverter::toFrame(celsius, c, QStringLiteral("float"));
    QCOMPARE(f.pixels, (QVector<quint16>{29315, 30865, 26815, 37340}));
    // A picture is not a measurement.
    try {
        InfraredFrameConverter::toFrame(cv::Mat(4, 4, CV_8UC3, cv::Scalar(1, 2, 3)), c, QStringLiteral("rgb.png"));
        QFAIL("an 8-bit colour image was accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).startsWith(QLatin1String("rgb.png: an 8-bit image")), e.what());
    }
}

void TestInfrared::csvFrames()
{
    // Camera software exports: a header, then rows of temperatures with ';' and decimal points.
    const cv::Mat m = InfraredFrameConverter::parseCsv("Frame 12\nTemperature [C]\n20.5;21.0;21.5\n22;22.5;23\n\n", QStringLiteral("f.csv"), false);
    QCOMPARE(m.rows, 2);
    QCOMPARE(m.cols, 3);
    QCOMPARE(m.at<double>(1, 2), 23.0);
    const cv::Mat k = InfraredFrameConverter::parseCsv("100,200\n300,400\n", QStringLiteral("k.csv"), true);
    QCOMPARE(k.type(), CV_16UC1);
    QCOMPARE(k.at<quint16>(1, 0), static_cast<quint16>(300));
    auto error = [](const QByteArray &text, bool counts) {
        try {
            InfraredFrameConverter::parseCsv(text, QStringLiteral("bad.csv"), counts);
        } catch (const std::invalid_argument &e) {
            return QString::fromUtf8(e.what());
        }
        return QString();
    };
    QCOMPARE(error("1,2,3\n4,5\n", false), QStringLiteral("bad.csv: line 2: 2 values, the frame's first row has 3"));
    QCOMPARE(error("1,2\n3,x\n", false), QStringLiteral("bad.csv: line 2: \"x\" is not a number"));
    QCOMPARE(error("1,2\n3,70000\n", true), QStringLiteral("bad.csv: line 2: 70000 is not a 16-bit count"));
    QCOMPARE(error("header only\n", false), QStringLiteral("bad.csv: no frame (no line of numbers)"));
}

void TestInfrared::folderWrittenDuringTheTest()
{
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString folder = dir.filePath(QStringLiteral("export"));
    QVERIFY(QDir().mkpath(folder));
    // An old frame already in the folder is not part of the recording.
    cv::Mat old(4, 6, CV_16UC1, cv::Scalar(30000));
    QVERIFY(cv::imwrite(QDir(folder).filePath(QStringLiteral("old.png")).toStdString(), old));
    InfraredFolderDevice d(QStringLiteral("camera"),
                           InfraredFolderDevice::Config::fromJson(json(QStringLiteral(R"({"folder":"%1","poll_s":0.05,"settle_s":0.5,
        "calibration":{"scale":0.01,"offset":-273.15,"screw_line_px":[0,2,5,2],"screw_line_m":[0,0.8]}})").arg(folder)),
                                                                  QStringLiteral("devices[0]")));
    SessionClock clock;
    clock.start();
    d.open();
    d.start(clock);
    QVector<IrFrame> frames;
    QVector<EventRecord> events;
    auto poll = [&](double wall_s) {
        QElapsedTimer t;
        t.start();
        while (t.elapsed() < wall_s * 1000.0) {
            const DeviceBlock b = d.read(0.1);
            frames += b.frames;
            events += b.events;
        }
    };
    poll(0.2);
    QVERIFY(frames.isEmpty());
    // Frames written while recording: a 16-bit TIFF, a 16-bit PNG, a CSV of temperatures.
    cv::Mat tif(4, 6, CV_16UC1);
    for (int r = 0; r < 4; ++r)
        for (int k = 0; k < 6; ++k)
            tif.at<quint16>(r, k) = static_cast<quint16>(29315 + 10 * r + k);
    const double writtenAt = clock.now_s();
    QVERIFY(cv::imwrite(QDir(folder).filePath(QStringLiteral("f001.tif")).toStdString(), tif));
    QVERIFY(cv::imwrite(QDir(folder).filePath(QStringLiteral("f002.png")).toStdString(), tif + 100));
    writeFile(QDir(folder).filePath(QStringLiteral("f003.csv")), "20.0,21.0\n22.0,23.5\n");
    // A frame still being written: half of it now, the rest later; only the whole file counts.
    const QByteArray full = "20,20,20\n20,20,20\n20,20,20\n";
    writeFile(QDir(folder).filePath(QStringLiteral("f004.csv")), full.left(10));
    writeFile(QDir(folder).filePath(QStringLiteral("notes.txt")), "not a frame");
    writeFile(QDir(folder).filePath(QStringLiteral("broken.tif")), "II*\0garbage");
    poll(0.1);
    {
        QFile f(QDir(folder).filePath(QStringLiteral("f004.csv")));
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(full);
    }
    poll(1.4);
    QStringList names;
    for (const IrFrame &f : frames)
        names << f.sourceName;
    names.sort();
    QCOMPARE(names, (QStringList{QStringLiteral("f001.tif"), QStringLiteral("f002.png"), QStringLiteral("f003.csv"), QStringLiteral("f004.csv")}));
    for (const IrFrame &f : frames) {
        if (f.sourceName == QLatin1String("f001.tif")) {
            QCOMPARE(f.width, 6);
            QCOMPARE(f.pixels[3 * 6 + 5], static_cast<quint16>(29315 + 35));
            // Stamped by the file's modification time on the session clock (1 s file time resolution at worst).
            QVERIFY2(std::fabs(f.t - writtenAt) < 1.1, qPrintable(QStringLiteral("stamped %1, written at %2").arg(f.t).arg(writtenAt)));
        }
        if (f.sourceName == QLatin1String("f002.png"))
            QCOMPARE(f.pixels[0], static_cast<quint16>(29415));
        if (f.sourceName == QLatin1String("f003.csv"))
            QCOMPARE(f.pixels, (QVector<quint16>{29315, 29415, 29515, 29665}));
        if (f.sourceName == QLatin1String("f004.csv")) {
            QCOMPARE(f.height, 3); // the whole file, never the half
            QCOMPARE(f.width, 3);
        }
    }
    for (int i = 1; i < frames.size(); ++i)
        QVERIFY(frames[i].t > frames[i - 1].t);
    QCOMPARE(events.size(), 1);
    QVERIFY2(events[0].label.contains(QLatin1String("skipped frame")) && events[0].label.contains(QLatin1String("broken.tif")),
             qPrintable(events[0].label));
    QCOMPARE(d.framesRead(), 4);
    // The share goes away: a DeviceError, the worker will retry.
    QVERIFY(QDir(folder).removeRecursively());
    QVERIFY_EXCEPTION_THROWN(d.read(0.1), DeviceError);
    QVERIFY_EXCEPTION_THROWN(d.open(), DeviceError);
}

void TestInfrared::uvcConfigurationAndMissingCamera()
{
    const UvcCameraDevice::Config c = UvcCameraDevice::Config::fromJson(
        json(QStringLiteral(R"({"camera":"/dev/video63","width":160,"height":120,"interval_s":5,"calibration":{"scale":0.01,"offset":-273.15}})")),
        QStringLiteral("devices[4]"));
    QCOMPARE(c.camera, QStringLiteral("/dev/video63"));
    QCOMPARE(c.fourcc, QStringLiteral("Y16 "));
    QCOMPARE(c.interval_s, 5.0);
    try {
        UvcCameraDevice::Config::fromJson(json(QStringLiteral(R"({"camera":"usb cam"})")), QStringLiteral("devices[4]"));
        QFAIL("a camera name was accepted");
    } catch (const std::invalid_argument &e) {
        QVERIFY2(QString::fromUtf8(e.what()).startsWith(QLatin1String("devices[4].camera: expected a camera index")), e.what());
    }
    QVERIFY_EXCEPTION_THROWN(UvcCameraDevice::Config::fromJson(json(QStringLiteral(R"({"fourcc":"Y16"})")), QStringLiteral("d")), std::invalid_argument);
    UvcCameraDevice d(QStringLiteral("uvc"), c);
    try {
        d.open();
        QFAIL("opened a camera that does not exist");
    } catch (const DeviceError &e) {
        QVERIFY2(QString::fromUtf8(e.what()).contains(QLatin1String("cannot open camera /dev/video63")), e.what());
    }
}

QTEST_GUILESS_MAIN(TestInfrared)
#include "tst_infrared.moc"
