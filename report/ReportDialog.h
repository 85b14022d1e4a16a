#pragma once
// The GUI's File > Test report: builds the report of the shown session, previews it and
// saves it as PDF or HTML (the same ReportBuilder/ReportWriter as `driftlab-cli report`),
// with an optional lab template folder.

#include "ReportDocument.h"
#include "ReportTemplate.h"

#include <QDialog>

class QLabel;
class QPrinter;
class QLineEdit;
class QTextBrowser;

namespace driftlab {

class SessionStore;

class ReportDialog : public QDialog {
    Q_OBJECT
public:
    ReportDialog(const SessionStore *store, qint64 sessionId, QWidget *parent = nullptr);

    // Rebuilds the report with the template folder (empty: built-in); false and a message in
    // the dialog if the template or the session cannot be read.
    bool rebuild(const QString &templateFolder);
    // Writes the report (PDF or HTML by suffix); false and a message on failure.
    bool save(const QString &path);
    // Prints the report on `printer` (the PDF's pages: A4 layout, page numbers); false and a
    // message on failure. The Print... button asks for the printer first.
    bool print(QPrinter &printer);
    QTextBrowser *preview() const { return m_preview; }
    QString message() const;

private:
    void chooseTemplate();
    void saveAs(const QString &suffix);

    const SessionStore *m_store;
    qint64 m_session;
    ReportTemplate m_template;
    ReportDocument m_document;
    bool m_built = false;
    QLineEdit *m_templateFolder;
    QTextBrowser *m_preview;
    QLabel *m_status;
};

} // namespace driftlab
