#include "HelpBrowser.h"

#include "ScreenFit.h"

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
    m_browser->setOpenExternalLinks(true);
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

QString HelpBrowser::currentDocument() const
{
    return QFileInfo(m_browser->source().path()).fileName();
}

} // namespace driftlab
