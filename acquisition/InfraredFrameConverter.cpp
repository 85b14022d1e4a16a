#include "InfraredFrameConverter.h"

#include <QLocale>
#include <QRegularExpression>

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace driftlab {

namespace {
[[noreturn]] void refuse(const QString &source, const QString &what)
{
    throw std::invalid_argument(QStringLiteral("%1: %2").arg(source, what).toStdString());
}
} // namespace

IrFrame InfraredFrameConverter::toFrame(const cv::Mat &image, const InfraredCalibration &cal, const QString &source, int width, int height)
{
    if (image.empty())
        refuse(source, QStringLiteral("empty image"));
    IrFrame f;
    f.sourceName = source;
    cv::Mat counts;
    if (image.type() == CV_16UC1) {
        counts = image;
    } else if (image.type() == CV_8UC2) {
        counts = cv::Mat(image.rows, image.cols, CV_16UC1);
        for (int r = 0; r < image.rows; ++r) {
            const uchar *in = image.ptr<uchar>(r);
            quint16 *out = counts.ptr<quint16>(r);
            for (int c = 0; c < image.cols; ++c)
                out[c] = static_cast<quint16>(in[2 * c] | (in[2 * c + 1] << 8));
        }
    } else if (image.type() == CV_8UC1 && image.rows == 1 && width > 0 && height > 0 &&
               static_cast<long long>(image.cols) == 2LL * width * height) {
        counts = cv::Mat(height, width, CV_16UC1);
        const uchar *in = image.ptr<uchar>(0);
        for (int r = 0; r < height; ++r) {
            quint16 *out = counts.ptr<quint16>(r);
            for (int c = 0; c < width; ++c) {
                const long long i = 2LL * (static_cast<long long>(r) * width + c);
                out[c] = static_cast<quint16>(in[i] | (in[i + 1] << 8));
            }
        }
    } else if (image.type() == CV_32FC1 || image.type() == CV_64FC1) {
        cv::Mat celsius;
        image.convertTo(celsius, CV_64FC1);
        counts = cv::Mat(image.rows, image.cols, CV_16UC1);
        for (int r = 0; r < image.rows; ++r) {
            const double *in = celsius.ptr<double>(r);
            quint16 *out = counts.ptr<quint16>(r);
            for (int c = 0; c < image.cols; ++c)
                out[c] = cal.count(in[c]);
        }
    } else if (image.depth() == CV_8U) {
        refuse(source, QStringLiteral("an 8-bit image (%1 channel(s)) carries no temperatures: set the camera to radiometric 16-bit (Y16) output or export radiometric TIFF/CSV")
                           .arg(image.channels()));
    } else {
        refuse(source, QStringLiteral("unsupported image type %1 (expected 16-bit counts or temperatures)").arg(image.type()));
    }
    f.width = counts.cols;
    f.height = counts.rows;
    f.pixels.resize(f.width * f.height);
    for (int r = 0; r < f.height; ++r)
        std::memcpy(f.pixels.data() + static_cast<qsizetype>(r) * f.width, counts.ptr<quint16>(r), sizeof(quint16) * static_cast<size_t>(f.width));
    return f;
}

cv::Mat InfraredFrameConverter::parseCsv(const QByteArray &text, const QString &source, bool asCounts)
{
    const QList<QByteArray> lines = text.split('\n');
    static const QRegularExpression sep(QStringLiteral("[,;\\t ]+"));
    std::vector<std::vector<double>> rows;
    int width = -1;
    int firstDataLine = -1;
    for (int i = 0; i < lines.size(); ++i) {
        const QString line = QString::fromUtf8(lines[i]).trimmed();
        if (line.isEmpty())
            continue;
        const QStringList cells = line.split(sep, Qt::SkipEmptyParts);
        std::vector<double> row;
        bool numeric = true;
        for (const QString &cell : cells) {
            bool ok = false;
            const double v = QLocale::c().toDouble(cell, &ok);
            if (!ok || !std::isfinite(v)) {
                numeric = false;
                if (firstDataLine >= 0)
                    refuse(source, QStringLiteral("line %1: \"%2\" is not a number").arg(i + 1).arg(cell.left(40)));
                break;
            }
            row.push_back(v);
        }
        if (!numeric) {
            if (i >= 50)
                refuse(source, QStringLiteral("line %1: no numeric frame found in the first 50 lines").arg(i + 1));
            continue; // header
        }
        if (firstDataLine < 0)
            firstDataLine = i;
        if (width < 0)
            width = static_cast<int>(row.size());
        else if (static_cast<int>(row.size()) != width)
            refuse(source, QStringLiteral("line %1: %2 values, the frame's first row has %3").arg(i + 1).arg(row.size()).arg(width));
        rows.push_back(std::move(row));
        if (rows.size() > 8192)
            refuse(source, QStringLiteral("line %1: more than 8192 rows").arg(i + 1));
    }
    if (rows.empty())
        refuse(source, QStringLiteral("no frame (no line of numbers)"));
    cv::Mat m(static_cast<int>(rows.size()), width, CV_64FC1);
    for (int r = 0; r < m.rows; ++r)
        for (int c = 0; c < width; ++c) {
            const double v = rows[static_cast<size_t>(r)][static_cast<size_t>(c)];
            if (asCounts && (v < 0 || v > 65535 || v != std::floor(v)))
                refuse(source, QStringLiteral("line %1: %2 is not a 16-bit count").arg(firstDataLine + 1 + r).arg(v));
            m.at<double>(r, c) = v;
        }
    if (asCounts) {
        cv::Mat counts;
        m.convertTo(counts, CV_16UC1);
        return counts;
    }
    return m;
}

} // namespace driftlab
