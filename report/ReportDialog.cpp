#include "ReportDialog.h"

#include "ReportBuilder.h"
#include "ReportWriter.h"
#include "SessionStore.h"

#include <QApplication>
#include <QDialogButtonBox>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPrintDialog>
#include <QPrinter>
#include <QPushButton>
#include <QScrollBar>
#include <QTextBrowser>
#include <QTextCursor>
#include <QVBoxLayout>

namespace driftlab {

ReportDialog::ReportDialog(const SessionStore *store, qint64 sessionId, QWidget *parent)
    : QDialog(parent), m_store(store), m_session(sessionId)
{
    setWindowTitle(tr("Test report of session %1").arg(sessionId));
    auto *layout = new QVBoxLayout(this);
    auto *row = new QHBoxLayout;
    row->addWidget(new QLabel(tr("Template:")));
    m_templateFolder = new QLineEdit;
    m_templateFolder->setPlaceholderText(tr("built-in (a folder with template.json, see docs/report.md)"));
    m_templateFolder->setReadOnly(true);
    row->addWidget(m_templateFolder, 1);
    auto *choose = new QPushButton(tr("Choose..."));
    connect(choose, &QPushButton::clicked, this, &ReportDialog::chooseTemplate);
    row->addWidget(choose);
    auto *builtIn = new QPushButton(tr("Built-in"));
    connect(builtIn, &QPushButton::clicked, this, [this] { rebuild(QString()); });
    row->addWidget(builtIn);
    layout->addLayout(row);
    m_preview = new QTextBrowser;
    m_preview->setObjectName(QStringLiteral("ReportPreview"));
    m_preview->setMinimumSize(560, 560);
    layout->addWidget(m_preview, 1);
    m_status = new QLabel;
    m_status->setWordWrap(true);
    layout->addWidget(m_status);
    auto *buttons = new QDialogButtonBox(QDialogButtonBox::Close);
    QPushButton *pdf = buttons->addButton(tr("Save &PDF..."), QDialogButtonBox::ActionRole);
    QPushButton *html = buttons->addButton(tr("Save &HTML..."), QDialogButtonBox::ActionRole);
    QPushButton *printButton = buttons->addButton(tr("P&rint..."), QDialogButtonBox::ActionRole);
    connect(printButton, &QPushButton::clicked, this, [this] {
        QPrinter printer(QPrinter::HighResolution);
        printer.setDocName(QStringLiteral("report-%1").arg(m_session));
        QPrintDialog dialog(&printer, this);
        dialog.setWindowTitle(tr("Print the test report"));
        if (dialog.exec() == QDialog::Accepted)
            print(printer);
    });
    connect(pdf, &QPushButton::clicked, this, [this] { saveAs(QStringLiteral("pdf")); });
    connect(html, &QPushButton::clicked, this, [this] { saveAs(QStringLiteral("html")); });
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    layout->addWidget(buttons);
    rebuild(QString());
}

QString ReportDialog::message() const { return m_status->text(); }

bool ReportDialog::rebuild(const QString &templateFolder)
{
    QApplication::setOverrideCursor(Qt::WaitCursor);
    QElapsedTimer timer;
    timer.start();
    try {
        m_template = ReportTemplate::load(templateFolder);
        m_document = ReportBuilder(*m_store, m_session, m_template).build();
        m_built = true;
        m_templateFolder->setText(templateFolder);
        ReportWriter(m_document, m_template).fillPreview(*m_preview->document(), 480);
        // The preview opens at the title, not where filling it left the cursor (the end).
        m_preview->setTextCursor(QTextCursor(m_preview->document()));
        m_preview->verticalScrollBar()->setValue(0);
        m_status->setText(tr("Report built in %1 s. The saved PDF and HTML hold the same content with vector figures.")
                              .arg(timer.elapsed() / 1000.0, 0, 'f', 1));
    } catch (const std::exception &e) {
        m_status->setText(tr("The report could not be built: %1").arg(QString::fromUtf8(e.what())));
        QApplication::restoreOverrideCursor();
        return false;
    }
    QApplication::restoreOverrideCursor();
    return true;
}

bool ReportDialog::save(const QString &path)
{
    if (!m_built)
        return false;
    try {
        ReportWriter(m_document, m_template).write(path);
    } catch (const std::exception &e) {
        m_status->setText(tr("Not saved: %1").arg(QString::fromUtf8(e.what())));
        return false;
    }
    m_status->setText(tr("Saved %1").arg(path));
    return true;
}

bool ReportDialog::print(QPrinter &printer)
{
    if (!m_built)
        return false;
    QApplication::setOverrideCursor(Qt::WaitCursor);
    try {
        ReportWriter(m_document, m_template).print(printer, printer.resolution());
    } catch (const std::exception &e) {
        QApplication::restoreOverrideCursor();
        m_status->setText(tr("Not printed: %1").arg(QString::fromUtf8(e.what())));
        return false;
    }
    QApplication::restoreOverrideCursor();
    m_status->setText(printer.outputFileName().isEmpty() ? tr("Sent to %1").arg(printer.printerName())
                                                         : tr("Printed to %1").arg(printer.outputFileName()));
    return true;
}

void ReportDialog::chooseTemplate()
{
    const QString dir = QFileDialog::getExistingDirectory(this, tr("Report template folder"), m_templateFolder->text());
    if (!dir.isEmpty())
        rebuild(dir);
}

void ReportDialog::saveAs(const QString &suffix)
{
    const QString filter = suffix == QLatin1String("pdf") ? tr("PDF (*.pdf)") : tr("HTML (*.html *.htm)");
    QString path = QFileDialog::getSaveFileName(this, tr("Save report"), QStringLiteral("report-%1.%2").arg(m_session).arg(suffix), filter);
    if (path.isEmpty())
        return;
    if (!ReportWriter::supportedSuffix(path))
        path += QLatin1Char('.') + suffix;
    save(path);
}

} // namespace driftlab
