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
// the file and line (fuzzable). read() checks a file of any size the same way with a memory
// bound that does not depend on its size (one bit per deviation, at most 125 MB for the
// largest Run-count x targets a file may declare) and keeps no deviations: forEachRun()
// reads them again from the device, run by run.

#include <QByteArray>
#include <QDateTime>
#include <QMap>
#include <QString>
#include <QVector>

#include <functional>
#include <stdexcept>

class QIODevice;

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
    QVector<QVector<double>> deviations_um; // [run - 1][target - 1]; empty after read()
    qint64 deviationCount = 0;           // runCount x targets once checked
    QDateTime date;                      // USER-TEXT Date (or ENVIRONMENT Date Time), local time; invalid if none
    int dateLine = 0;

    // The whole file in memory, deviations included (files up to 64 MiB).
    static RtlFile parse(const QByteArray &text, const QString &source);
    // Checks the file on `in` (seekable: it is read twice) exactly as parse() does, without
    // keeping its deviations; forEachRun() reads them from `in` again, which must stay open.
    static RtlFile read(QIODevice &in, const QString &source);
    // Every run in order (1-based run number, deviations in um indexed by target - 1). For a
    // file from read(): one more pass over the device when each run's lines are together and
    // the runs ascend (as the laser software writes them), else one pass per ~4 M deviations.
    // Throws RtlError if the device no longer holds what read() checked.
    void forEachRun(const std::function<void(int run, const QVector<double> &deviations_um)> &visit) const;
    // Direction of run r (1-based) as the file's flags suggest: "+" / "-" for a
    // bidirectional test (odd runs forward, even runs back), "+" unidirectional, "" unknown.
    QString direction(int run) const;
    bool bidirectional() const { return flags.size() >= 2 && flags[1] == 0 && runCount % 2 == 0; }

private:
    QIODevice *m_device = nullptr; // set by read(): where forEachRun() finds the deviations
    bool m_runsInOrder = false;    // each run's lines together, runs ascending
};

} // namespace driftlab
