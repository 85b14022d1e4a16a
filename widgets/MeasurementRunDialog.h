#pragma once
// A laser-interferometer run entered by the technician while the recording runs: the
// targets of the run (first target, step, count, or from an .rtl file), then the measured
// deviation of each target typed in as the laser software shows it, or pasted (one value
// per line, or "position <tab> deviation" lines copied from the laser software). Each
// deviation is stamped on the session clock when it is entered (the time stays editable);
// "Commit run" hands the run to the recorder as interferometer points with the next run
// number and an event. Nothing half-entered is committed: a target without a deviation
// stops the commit with a message naming it.

#include "StorageTypes.h"

#include <QDialog>

#include <functional>

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QSpinBox;
class QTableWidget;

namespace driftlab {

class MeasurementRunDialog : public QDialog {
    Q_OBJECT
public:
    using Now = std::function<double()>;
    using Commit = std::function<void(const QVector<InterferometerPoint> &, const QString &note)>;

    MeasurementRunDialog(Now now, Commit commit, QWidget *parent = nullptr, int firstRun = 0);

    void setTargets(const QVector<double> &targets_mm);
    QVector<double> targets() const;
    void setDirection(const QString &direction); // "+", "-" or ""
    // Types a deviation into a row (as the technician does); stamps it now.
    bool enterDeviation(int row, const QString &text);
    // Pastes lines from the current row on (or matched by position when lines have two values).
    int paste(const QString &text, int fromRow = 0);
    bool loadRtl(const QString &path, int run);
    bool commitRun();
    int nextRun() const { return m_run; }
    QString lastError() const { return m_error; }
    int rowCount() const;

private:
    void fillTargets();
    void cellEdited(int row, int column);
    void timeEdited(int row);
    void setError(const QString &message);

    Now m_now;
    Commit m_commit;
    int m_run;
    bool m_updating = false;
    QString m_error;
    QDoubleSpinBox *m_first, *m_step;
    QSpinBox *m_count;
    QComboBox *m_direction;
    QTableWidget *m_table;
    QLabel *m_runLabel, *m_status;
};

} // namespace driftlab
