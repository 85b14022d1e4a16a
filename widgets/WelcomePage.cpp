#include "WelcomePage.h"

#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

namespace driftlab {

WelcomePage::WelcomePage(QWidget *parent)
    : QWidget(parent),
      m_database(new QLabel(this)),
      m_record(new QPushButton(tr("Record a simulated session"), this)),
      m_example(new QPushButton(tr("Open the example bundle"), this)),
      m_csv(new QPushButton(tr("Import a CSV table..."), this))
{
    setObjectName(QStringLiteral("WelcomePage"));
    auto *title = new QLabel(tr("<h2>No session yet</h2>"), this);
    m_database->setWordWrap(true);
    m_database->setTextInteractionFlags(Qt::TextSelectableByMouse);
    auto *grid = new QGridLayout;
    const QString notes[] = {
        tr("A simulated rig warms a ball screw for 10 minutes of test time (at 60 x speed): temperatures, "
           "probe elongation, interferometer runs. Watch it in the Acquisition dock."),
        tr("A recorded warm-up test with interferometer runs and infrared frames, imported as a session: "
           "every review view has data."),
        tr("A logger's table (temperatures and displacements over time): choose its columns, units and "
           "time format, then import."),
    };
    QPushButton *buttons[] = {m_record, m_example, m_csv};
    for (int i = 0; i < 3; ++i) {
        auto *note = new QLabel(notes[i], this);
        note->setWordWrap(true);
        buttons[i]->setMinimumWidth(buttons[i]->sizeHint().width());
        grid->addWidget(buttons[i], i, 0, Qt::AlignTop);
        grid->addWidget(note, i, 1);
    }
    grid->setColumnStretch(1, 1);
    grid->setHorizontalSpacing(16);
    grid->setVerticalSpacing(14);
    auto *box = new QWidget(this);
    box->setMaximumWidth(760);
    auto *inner = new QVBoxLayout(box);
    inner->addWidget(title);
    inner->addWidget(m_database);
    inner->addSpacing(8);
    inner->addLayout(grid);
    // Centred between stretches, not with Qt::AlignHCenter: an aligned item gets the height of
    // its size hint, two lines per note, and the notes were cut ("...choose its").
    auto *row = new QHBoxLayout;
    row->addStretch(1);
    row->addWidget(box);
    row->addStretch(1);
    auto *layout = new QVBoxLayout(this);
    layout->addStretch(1);
    layout->addLayout(row);
    layout->addStretch(2);
    connect(m_record, &QPushButton::clicked, this, &WelcomePage::recordSimulated);
    connect(m_example, &QPushButton::clicked, this, &WelcomePage::openExample);
    connect(m_csv, &QPushButton::clicked, this, &WelcomePage::importCsv);
    setDatabase(QString());
}

void WelcomePage::setDatabase(const QString &path)
{
    m_database->setText(path.isEmpty() ? tr("No database is open: the first session creates one in your data folder.")
                                       : tr("The database %1 holds no session. Begin with one of these:").arg(path));
}

} // namespace driftlab
