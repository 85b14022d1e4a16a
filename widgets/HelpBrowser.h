#pragma once
// Help > Documentation (F1): the user documentation shipped inside the application (the
// Markdown files of docs/ and README.md as Qt resources under :/docs), listed on the left
// and shown as formatted text with working links between them. No source-tree paths.

#include <QDialog>

class QListWidget;
class QTextBrowser;
class QUrl;

namespace driftlab {

class HelpBrowser : public QDialog {
    Q_OBJECT
public:
    // `root`: the resource folder with the .md files (":/docs" in the application).
    explicit HelpBrowser(const QString &root = QStringLiteral(":/docs"), QWidget *parent = nullptr);

    // The documents found (file names), README.md first; empty when none were shipped.
    QStringList documents() const { return m_documents; }
    // Shows a document by file name; false if it is not there.
    bool showDocument(const QString &name);
    QString currentDocument() const;
    // What a click on a link does: another shipped document (README's "docs/x.md" as well as
    // "x.md", with its #anchor) is shown here; http(s) and mailto open outside; anything else
    // (a source file of the checkout, "../resources/...") is not shipped: false, nothing opens.
    bool followLink(const QUrl &link);
    QTextBrowser *browser() const { return m_browser; }

private:
    QString m_root;
    QStringList m_documents;
    QListWidget *m_list;
    QTextBrowser *m_browser;
};

} // namespace driftlab
