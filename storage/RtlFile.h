#pragma once
// A Renishaw laser-interferometer linear test file (.rtl, the text format the Renishaw
// laser software saves a linear positioning test in):
//   HEADER::        File type : rtl, Owner, Version no
//   TARGET DATA::   Filetype, Target-count, Targets : (target positions in mm, possibly
//                   over several lines), Flags
//   USER-TEXT::     Machine, Serial No, Date, By, Axis, Location, TITLE (free text)
//   RUNS::          Run-count
//   DEVIATIONS::    Run Target Data: then one line "run target deviation" per measurement
//                   (deviation in um)
//   ENVIRONMENT::, EQUIPMENT::, other sections and EOF:: are kept or ignored.
// No sample file from Renishaw was available; the layout is the one independent
// third-party readers and writers of .rtl files use (see docs/acquisition.md). parse() is
// a plain function from bytes to the file; anything it cannot trust throws RtlError with
// the file and line (fuzzable).

#include <QByteArray>
#include <QDateTime>
#include <QMap>
#include <QString>
#include <QVector>

#include <stdexcept>

namespace driftlab {

class RtlError : public std::runtime_error {
public:
    RtlError(const QString &file, int line, const QString &what)
        : std::runtime_error((line > 0 ? QStringLiteral("%1: line %2: %3").arg(file).arg(line).arg(what)
                                       : QStringLiteral("%1: %2").arg(file, what))
                                 .toStdString()),
          m_line(line)
    {
    }
    int line() const { return m_line; }

private:
    int m_line;
};

class RtlFile {
public:
    QString source;
    QMap<QString, QString> header, userText, environment; // keys as written, values trimmed
    QVector<double> targets_mm;
    QVector<int> flags;                  // the TARGET DATA "Flags:" numbers, if any
    int runCount = 0;
    QVector<QVector<double>> deviations_um; // [run - 1][target - 1]
    QDateTime date;                      // USER-TEXT Date (or ENVIRONMENT Date Time), local time; invalid if none
    int dateLine = 0;

    static RtlFile parse(const QByteArray &text, const QString &source);
    // Direction of run r (1-based) as the file's flags suggest: "+" / "-" for a
    // bidirectional test (odd runs forward, even runs back), "+" unidirectional, "" unknown.
    QString direction(int run) const;
    bool bidirectional() const { return flags.size() >= 2 && flags[1] == 0 && runCount % 2 == 0; }
};

} // namespace driftlab
