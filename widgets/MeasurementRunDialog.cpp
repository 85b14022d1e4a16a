#include "MeasurementRunDialog.h"

#include "RtlFile.h"
#include "UnitLabels.h"

#include <QApplication>
#include <QClipboard>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QInputDialog>
#include <QKeyEvent>
#include <QLabel>
#include <QLocale>
#include <QPushButton>
#include <QRegularExpression>
#include <QShortcut>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>

#include <cmath>

namespace driftlab {

namespace {
enum Column { ColTarget, ColDeviation, ColTime, ColCount };

// The technician's decimal separator or the C locale's.
bool parseNumber(QString text, double &value)
{
    text = text.trimmed();
    bool ok = false;
    value = QLocale::c().toDouble(text, &ok);
    if (!ok)
        value = QLocale::system().toDouble(text, &ok);
    if (!ok)
        value = QLocale::c().toDouble(QString(text).replace(QLatin1Char(','), QLatin1Char('.')), &ok);
    return ok && std::isfinite(value);
}

// A target's session time: exact seconds in the item's data (the stamp keeps its fraction),
// h:mm:ss in its text.
void setTime(QTableWidgetItem *item, double seconds)
{
    item->setData(Qt::UserRole, seconds);
    item->setText(UnitLabels::clock(seconds));
    item->setBackground(QBrush());
}

bool timeOf(const QTableWidgetItem *item, double &seconds)
{
    const QVariant v = item->data(Qt::UserRole);
    bool ok = false;
    seconds = v.toDouble(&ok);
    return v.isValid() && ok;
}
} // namespace

MeasurementRunDialog::MeasurementRunDialog(Now now, Commit commit, QWidget *parent, int firstRun)
    : QDialog(parent), m_now(std::move(now)), m_commit(std::move(commit)), m_run(firstRun)
{
    setWindowTitle(tr("Interferometer measurement run"));
    m_first = new QDoubleSpinBox(this);
    m_first->setRange(-100000, 100000);
    m_first->setDecimals(3);
    m_first->setSuffix(tr(" mm"));
    m_step = new QDoubleSpinBox(this);
    m_step->setRange(-100000, 100000);
    m_step->setDecimals(3);
    m_step->setValue(50.0);
    m_step->setSuffix(tr(" mm"));
    m_count = new QSpinBox(this);
    m_count->setRange(1, 1000);
    m_count->setValue(11);
    m_direction = new QComboBox(this);
    m_direction->addItem(tr("forward (+)"), QStringLiteral("+"));
    m_direction->addItem(tr("reverse (-)"), QStringLiteral("-"));
    m_direction->addItem(tr("not recorded"), QString());
    auto *fill = new QPushButton(tr("Set targets"), this);
    auto *rtl = new QPushButton(tr("From .rtl file..."), this);
    auto *form = new QFormLayout;
    form->addRow(tr("First target"), m_first);
    form->addRow(tr("Step"), m_step);
    form->addRow(tr("Targets"), m_count);
    form->addRow(tr("Direction"), m_direction);
    auto *fb = new QHBoxLayout;
    fb->addWidget(fill);
    fb->addWidget(rtl);
    form->addRow(fb);
    m_table = new QTableWidget(0, ColCount, this);
    m_table->setHorizontalHeaderLabels({tr("Target (mm)"), tr("Thermal error (µm)"), tr("Time (h:mm:ss)")});
    m_table->horizontalHeader()->setStretchLastSection(true);
    m_table->resizeColumnsToContents(); // the headings whole ("Thermal error (µm)" was cut at 100 px)
    m_runLabel = new QLabel(this);
    m_status = new QLabel(tr("Type each deviation as the laser software shows it, or paste a column of values (Ctrl+V)."), this);
    m_status->setWordWrap(true);
    auto *commitButton = new QPushButton(tr("Commit run"), this);
    auto *close = new QPushButton(tr("Close"), this);
    auto *bottom = new QHBoxLayout;
    bottom->addWidget(m_runLabel);
    bottom->addStretch();
    bottom->addWidget(commitButton);
    bottom->addWidget(close);
    auto *layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addWidget(m_table, 1);
    layout->addWidget(m_status);
    layout->addLayout(bottom);
    resize(520, 640);

    connect(fill, &QPushButton::clicked, this, &MeasurementRunDialog::fillTargets);
    connect(rtl, &QPushButton::clicked, this, [this] {
        const QString f = QFileDialog::getOpenFileName(this, tr("Renishaw linear test"), QString(), tr("Renishaw linear test (*.rtl)"));
        if (f.isEmpty())
            return;
        bool ok = false;
        const int run = QInputDialog::getInt(this, tr("Run"), tr("Run of the file to enter"), 1, 1, 10000, 1, &ok);
        if (ok)
            loadRtl(f, run);
    });
    connect(m_table, &QTableWidget::cellChanged, this, &MeasurementRunDialog::cellEdited);
    connect(commitButton, &QPushButton::clicked, this, &MeasurementRunDialog::commitRun);
    connect(close, &QPushButton::clicked, this, &QDialog::reject);
    auto *pasteShortcut = new QShortcut(QKeySequence::Paste, m_table);
    connect(pasteShortcut, &QShortcut::activated, this, [this] {
        paste(QApplication::clipboard()->text(), std::max(0, m_table->currentRow()));
    });
    fillTargets();
}

int MeasurementRunDialog::rowCount() const
{
    return m_table->rowCount();
}

void MeasurementRunDialog::setError(const QString &message)
{
    m_error = message;
    m_status->setText(message.isEmpty() ? QString() : QStringLiteral("<span style='color:#b00020'>%1</span>").arg(message.toHtmlEscaped()));
}

void MeasurementRunDialog::fillTargets()
{
    QVector<double> t;
    for (int i = 0; i < m_count->value(); ++i)
        t.push_back(m_first->value() + i * m_step->value());
    setTargets(t);
}

void MeasurementRunDialog::setTargets(const QVector<double> &targets_mm)
{
    m_updating = true;
    if (!targets_mm.isEmpty()) { // the fields show the run's targets
        m_first->setValue(targets_mm.first());
        if (targets_mm.size() > 1)
            m_step->setValue(targets_mm[1] - targets_mm[0]);
        m_count->setValue(targets_mm.size());
    }
    m_table->setRowCount(targets_mm.size());
    for (int r = 0; r < targets_mm.size(); ++r) {
        m_table->setItem(r, ColTarget, new QTableWidgetItem(QString::number(targets_mm[r], 'f', 3)));
        m_table->setItem(r, ColDeviation, new QTableWidgetItem);
        m_table->setItem(r, ColTime, new QTableWidgetItem);
    }
    m_updating = false;
    m_runLabel->setText(tr("Run %1").arg(m_run));
}

QVector<double> MeasurementRunDialog::targets() const
{
    QVector<double> t;
    for (int r = 0; r < m_table->rowCount(); ++r)
        t.push_back(m_table->item(r, ColTarget)->text().toDouble());
    return t;
}

void MeasurementRunDialog::setDirection(const QString &direction)
{
    m_direction->setCurrentIndex(std::max(0, m_direction->findData(direction)));
}

void MeasurementRunDialog::cellEdited(int row, int column)
{
    if (m_updating)
        return;
    if (column == ColTime) {
        timeEdited(row);
        return;
    }
    if (column != ColDeviation)
        return;
    QTableWidgetItem *item = m_table->item(row, ColDeviation);
    double v = 0.0;
    m_updating = true;
    if (item->text().trimmed().isEmpty()) {
        m_table->item(row, ColTime)->setText(QString());
        m_table->item(row, ColTime)->setData(Qt::UserRole, QVariant());
        item->setBackground(QBrush());
    } else if (parseNumber(item->text(), v)) {
        item->setBackground(QBrush());
        if (m_table->item(row, ColTime)->text().isEmpty())
            setTime(m_table->item(row, ColTime), m_now());
        setError(QString());
    } else {
        item->setBackground(QColor(255, 205, 210));
        setError(tr("target %1 mm: \"%2\" is not a number").arg(m_table->item(row, ColTarget)->text(), item->text()));
    }
    m_updating = false;
}

void MeasurementRunDialog::timeEdited(int row)
{
    // The technician corrects a stamp: h:mm:ss (or seconds, "90 min") on the session's clock.
    QTableWidgetItem *item = m_table->item(row, ColTime);
    QString why;
    m_updating = true;
    if (item->text().trimmed().isEmpty()) {
        item->setData(Qt::UserRole, QVariant());
        item->setBackground(QBrush());
    } else if (const std::optional<double> t = UnitLabels::parseClock(item->text(), &why)) {
        setTime(item, *t);
        setError(QString());
    } else {
        item->setData(Qt::UserRole, QVariant());
        item->setBackground(QColor(255, 205, 210));
        setError(tr("target %1 mm: session time %2").arg(m_table->item(row, ColTarget)->text(), why));
    }
    m_updating = false;
}

bool MeasurementRunDialog::enterDeviation(int row, const QString &text)
{
    if (row < 0 || row >= m_table->rowCount())
        return false;
    m_table->item(row, ColDeviation)->setText(text); // cellChanged stamps it
    double v = 0.0;
    return parseNumber(text, v);
}

int MeasurementRunDialog::paste(const QString &text, int fromRow)
{
    static const QRegularExpression sep(QStringLiteral("[\\t;]+|\\s+"));
    int row = fromRow, entered = 0;
    for (const QString &rawLine : text.split(QLatin1Char('\n'))) {
        const QString line = rawLine.trimmed();
        if (line.isEmpty())
            continue;
        const QStringList parts = line.split(sep, Qt::SkipEmptyParts);
        double pos = 0.0, dev = 0.0;
        if (parts.size() >= 2 && parseNumber(parts[0], pos) && parseNumber(parts.last(), dev)) {
            // "position deviation": the row of that target
            int match = -1;
            for (int r = 0; r < m_table->rowCount() && match < 0; ++r)
                if (std::fabs(m_table->item(r, ColTarget)->text().toDouble() - pos) < 1e-3)
                    match = r;
            if (match < 0) {
                setError(tr("pasted line \"%1\": no target at %2 mm").arg(line).arg(pos));
                continue;
            }
            enterDeviation(match, parts.last());
            ++entered;
        } else if (parts.size() == 1) {
            if (row >= m_table->rowCount()) {
                setError(tr("pasted more values than targets: \"%1\" and after not entered").arg(line));
                break;
            }
            enterDeviation(row++, parts[0]);
            ++entered;
        } else {
            setError(tr("pasted line \"%1\" is neither a deviation nor \"position deviation\"").arg(line));
        }
    }
    return entered;
}

bool MeasurementRunDialog::loadRtl(const QString &path, int run)
{
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) {
        setError(tr("%1: %2").arg(path, f.errorString()));
        return false;
    }
    try {
        const RtlFile rtl = RtlFile::parse(f.readAll(), path);
        if (run < 1 || run > rtl.runCount) {
            setError(tr("%1 has runs 1 to %2").arg(path).arg(rtl.runCount));
            return false;
        }
        setTargets(rtl.targets_mm);
        setDirection(rtl.direction(run));
        for (int t = 0; t < rtl.targets_mm.size(); ++t)
            enterDeviation(t, QString::number(rtl.deviations_um[run - 1][t], 'g', 10));
        return true;
    } catch (const RtlError &e) {
        setError(QString::fromUtf8(e.what()));
        return false;
    }
}

bool MeasurementRunDialog::commitRun()
{
    QVector<InterferometerPoint> points;
    const QString direction = m_direction->currentData().toString();
    for (int r = 0; r < m_table->rowCount(); ++r) {
        double dev = 0.0, t = 0.0;
        const QString target = m_table->item(r, ColTarget)->text();
        if (!parseNumber(m_table->item(r, ColDeviation)->text(), dev)) {
            setError(tr("target %1 mm has no deviation: enter it or remove the row (nothing committed)").arg(target));
            return false;
        }
        if (!timeOf(m_table->item(r, ColTime), t)) {
            setError(tr("target %1 mm has no valid time (nothing committed)").arg(target));
            return false;
        }
        InterferometerPoint p;
        p.t = t;
        p.run = m_run;
        p.position_mm = target.toDouble();
        p.error_um = dev;
        p.direction = direction;
        points.push_back(p);
    }
    if (points.isEmpty()) {
        setError(tr("no targets"));
        return false;
    }
    std::stable_sort(points.begin(), points.end(), [](const InterferometerPoint &a, const InterferometerPoint &b) { return a.t < b.t; });
    m_commit(points, tr("interferometer run %1 entered by the technician (%2 targets)").arg(m_run).arg(points.size()));
    ++m_run;
    setError(QString());
    m_status->setText(tr("Run %1 committed (%2 points). Enter the next run.").arg(m_run - 1).arg(points.size()));
    // Same targets for the next run, deviations cleared.
    setTargets(targets());
    return true;
}

} // namespace driftlab
