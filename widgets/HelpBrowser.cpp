#include "HelpBrowser.h"

#include "ScreenFit.h"

#include <QDesktopServices>
#include <QDialogButtonBox>
#include <QDir>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QListWidget>
#include <QSplitter>
#include <QTextBrowser>
#include <QUrl>
#include <QVBoxLayout>

namespace driftlab {

HelpBrowser::HelpBrowser(const QString &root, QWidget *parent)
    : QDialog(parent), m_root(root), m_list(new QListWidget(this)), m_browser(new QTextBrowser(this))
{
    setWindowTitle(tr("DriftLab documentation"));
    m_documents = QDir(root).entryList({QStringLiteral("*.md")}, QDir::Files, QDir::Name);
    if (m_documents.removeAll(QStringLiteral("README.md")) > 0)
        m_documents.prepend(QStringLiteral("README.md"));
    m_list->addItems(m_documents);
    // Links are resolved here, not against the resource folder: README.md's "docs/x.md"
    // named a folder of the source tree that the shipped documentation does not have.
    m_browser->setOpenLinks(false);
    connect(m_browser, &QTextBrowser::anchorClicked, this, &HelpBrowser::followLink);
    m_browser->setSearchPaths({root});
    auto *split = new QSplitter(this);
    split->addWidget(m_list);
    split->addWidget(m_browser);
    split->setStretchFactor(1, 4);
    split->setChildrenCollapsible(false);
    auto *buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
    auto *layout = new QVBoxLayout(this);
    layout->addWidget(split, 1);
    layout->addWidget(buttons);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(m_list, &QListWidget::currentTextChanged, this, [this](const QString &name) {
        if (!name.isEmpty() && name != currentDocument())
            showDocument(name);
    });
    // A link to another document selects it in the list too.
    connect(m_browser, &QTextBrowser::sourceChanged, this, [this] {
        const QList<QListWidgetItem *> items = m_list->findItems(currentDocument(), Qt::MatchExactly);
        if (!items.isEmpty())
            m_list->setCurrentItem(items.first());
    });
    ScreenFit::resize(this, QSize(1100, 800));
    if (!m_documents.isEmpty())
        showDocument(m_documents.first());
    else
        m_browser->setPlainText(tr("No documentation was shipped with this build."));
}

bool HelpBrowser::showDocument(const QString &name)
{
    if (!m_documents.contains(name))
        return false;
    const QString path = m_root + QLatin1Char('/') + name;
    m_browser->setSource(path.startsWith(QLatin1Char(':')) ? QUrl(QStringLiteral("qrc") + path) : QUrl::fromLocalFile(path),
                         QTextDocument::MarkdownResource);
    return true;
}

bool HelpBrowser::followLink(const QUrl &link)
{
    const QString scheme = link.scheme();
    if (scheme == QLatin1String("http") || scheme == QLatin1String("https") || scheme == QLatin1String("mailto"))
        return QDesktopServices::openUrl(link);
    if (!link.isRelative() && scheme != QLatin1String("qrc") && scheme != QLatin1String("file"))
        return false;
    const QString path = link.path();
    if (path.isEmpty() && link.hasFragment()) { // an anchor of the document shown
        m_browser->scrollToAnchor(link.fragment());
        return true;
    }
    // Only "x.md" or "docs/x.md" of the shipped set; not "../resources/..." or "src/x.md".
    const QString folder = QFileInfo(path).path();
    if (link.isRelative() && folder != QLatin1String(".") && folder != QLatin1String("docs"))
        return false;
    const QString name = QFileInfo(path).fileName();
    if (!showDocument(name))
        return false;
    if (link.hasFragment())
        m_browser->scrollToAnchor(link.fragment());
    return true;
}

QString HelpBrowser::currentDocument() const
{
    return QFileInfo(m_browser->source().path()).fileName();
}

} // namespace driftlab
