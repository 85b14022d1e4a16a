#include "InfraredFrame.h"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace driftlab {

namespace {
bool endsWith(std::string s, const std::string &suffix)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
} // namespace

cv::Mat InfraredFrame::countsToTemperature(const cv::Mat &counts16, const InfraredCalibration &c)
{
    cv::Mat t;
    counts16.convertTo(t, CV_32F, c.scale, c.offset);
    return t;
}

cv::Mat InfraredFrame::readTemperature(const std::string &path, const InfraredCalibration &calibration)
{
    if (endsWith(path, ".csv"))
        return readRadiometricCsv(path);
    const cv::Mat img = cv::imread(path, cv::IMREAD_UNCHANGED);
    if (img.empty())
        throw std::runtime_error(path + ": not a readable PNG/TIFF image");
    if (img.type() != CV_16UC1)
        throw std::runtime_error(path + ": expected a single-channel 16-bit image, got " + std::to_string(img.channels()) +
                                 " channel(s) of " + std::to_string(8 * static_cast<int>(img.elemSize1())) + " bit");
    return countsToTemperature(img, calibration);
}

cv::Mat InfraredFrame::readRadiometricCsv(const std::string &path)
{
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error(path + ": cannot open");
    std::vector<std::vector<float>> rows;
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos)
            continue;
        const char sep = line.find(';') != std::string::npos ? ';' : ',';
        std::vector<float> row;
        std::stringstream ss(line);
        std::string cell;
        int col = 0;
        while (std::getline(ss, cell, sep)) {
            ++col;
            std::replace(cell.begin(), cell.end(), ',', '.');
            const char *begin = cell.c_str();
            char *end = nullptr;
            errno = 0;
            const double v = std::strtod(begin, &end);
            while (end && *end && std::isspace(static_cast<unsigned char>(*end)))
                ++end;
            if (end == begin || (end && *end) || errno == ERANGE || v < -273.15 || v > 3000.0)
                throw std::runtime_error(path + ": line " + std::to_string(lineNo) + ", column " + std::to_string(col) +
                                         ": '" + cell + "' is not a temperature in \u00b0C");
            row.push_back(static_cast<float>(v));
        }
        if (!rows.empty() && row.size() != rows.front().size())
            throw std::runtime_error(path + ": line " + std::to_string(lineNo) + " has " + std::to_string(row.size()) +
                                     " values, expected " + std::to_string(rows.front().size()));
        rows.push_back(std::move(row));
    }
    if (rows.empty())
        throw std::runtime_error(path + ": no temperatures");
    cv::Mat t(static_cast<int>(rows.size()), static_cast<int>(rows.front().size()), CV_32F);
    for (int r = 0; r < t.rows; ++r)
        std::copy(rows[static_cast<size_t>(r)].begin(), rows[static_cast<size_t>(r)].end(), t.ptr<float>(r));
    return t;
}

} // namespace driftlab
