#include "ReportTemplate.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>

#include <stdexcept>

static void initReportResources() { Q_INIT_RESOURCE(report); }

namespace driftlab {

namespace {

[[noreturn]] void fail(const QString &message) { throw std::invalid_argument(message.toStdString()); }

QString text(const QJsonObject &o, const QString &key, const QString &file, const QString &fallback)
{
    const QJsonValue v = o.value(key);
    if (v.isUndefined())
        return fallback;
    if (!v.isString())
        fail(QStringLiteral("%1: field '%2' must be a string").arg(file, key));
    return v.toString();
}

} // namespace

ReportTemplate ReportTemplate::load(const QString &folder)
{
    initReportResources();
    ReportTemplate t;
    t.apply(defaultFolder(), true);
    if (!folder.isEmpty())
        t.apply(folder, false);
    return t;
}

void ReportTemplate::apply(const QString &folder, bool isDefault)
{
    const QDir dir(folder);
    if (!dir.exists())
        fail(QStringLiteral("%1: the template folder does not exist").arg(folder));
    const QString file = dir.filePath(QStringLiteral("template.json"));
    QFile f(file);
    if (!f.open(QIODevice::ReadOnly))
        fail(QStringLiteral("%1: cannot read the template (%2)").arg(file, f.errorString()));
    QJsonParseError error{};
    const QJsonDocument doc = QJsonDocument::fromJson(f.readAll(), &error);
    if (error.error != QJsonParseError::NoError || !doc.isObject())
        fail(QStringLiteral("%1: not a JSON object (%2 at offset %3)").arg(file, error.errorString()).arg(error.offset));
    const QJsonObject o = doc.object();
    static const QStringList known = {QStringLiteral("lab_name"), QStringLiteral("logo"), QStringLiteral("language"),
                                      QStringLiteral("title"), QStringLiteral("headings")};
    for (const QString &key : o.keys())
        if (!known.contains(key))
            fail(QStringLiteral("%1: unknown field '%2' (known: %3)").arg(file, key, known.join(QStringLiteral(", "))));
    m_labName = text(o, QStringLiteral("lab_name"), file, m_labName);
    m_title = text(o, QStringLiteral("title"), file, m_title);
    m_language = text(o, QStringLiteral("language"), file, m_language);
    const QJsonValue headings = o.value(QStringLiteral("headings"));
    if (!headings.isUndefined() && !headings.isObject())
        fail(QStringLiteral("%1: field 'headings' must be an object of section key: heading").arg(file));
    const QJsonObject h = headings.toObject();
    for (auto it = h.begin(); it != h.end(); ++it) {
        if (!isDefault && !m_headings.contains(it.key()))
            fail(QStringLiteral("%1: headings: unknown section '%2' (known: %3)")
                     .arg(file, it.key(), QStringList(m_headings.keys()).join(QStringLiteral(", "))));
        if (!it.value().isString())
            fail(QStringLiteral("%1: headings.%2 must be a string").arg(file, it.key()));
        m_headings.insert(it.key(), it.value().toString());
    }
    if (o.contains(QStringLiteral("logo"))) {
        const QString name = text(o, QStringLiteral("logo"), file, QString());
        m_logo.clear();
        m_logoMime.clear();
        if (name.isEmpty())
            return; // "logo": "" removes the default logo
        QFile logo(dir.filePath(name));
        if (!logo.open(QIODevice::ReadOnly))
            fail(QStringLiteral("%1: logo '%2' cannot be read (%3)").arg(file, name, logo.errorString()));
        const QString suffix = QFileInfo(name).suffix().toLower();
        if (suffix == QLatin1String("svg"))
            m_logoMime = QStringLiteral("image/svg+xml");
        else if (suffix == QLatin1String("png"))
            m_logoMime = QStringLiteral("image/png");
        else if (suffix == QLatin1String("jpg") || suffix == QLatin1String("jpeg"))
            m_logoMime = QStringLiteral("image/jpeg");
        else
            fail(QStringLiteral("%1: logo '%2': use a .svg, .png or .jpg file").arg(file, name));
        m_logo = logo.readAll();
    }
}

} // namespace driftlab
