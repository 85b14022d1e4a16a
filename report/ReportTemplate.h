#pragma once
// The look of a test report that a lab edits without recompiling: a folder holding
// template.json (lab name, report title, language, the section headings) and an optional
// logo (PNG, JPEG or SVG). Headings a lab template leaves out come from the default
// template (resources/report/, compiled in as ":/report/default").

#include <QByteArray>
#include <QMap>
#include <QString>
#include <QStringList>

namespace driftlab {

class ReportTemplate {
public:
    // The folder's template.json on top of the default; an empty folder = the default alone.
    // Throws std::invalid_argument naming the file and field that is wrong (unknown heading
    // key, non-string value, missing logo file, unreadable JSON).
    static ReportTemplate load(const QString &folder = QString());
    static QString defaultFolder() { return QStringLiteral(":/report/default"); }

    QString labName() const { return m_labName; }
    QString title() const { return m_title; }
    QString language() const { return m_language; }
    // The heading for a section key (see headingKeys()); the key itself if none is known.
    QString heading(const QString &key) const { return m_headings.value(key, key); }
    QStringList headingKeys() const { return m_headings.keys(); }
    // The logo file's bytes and MIME type (image/svg+xml, image/png, image/jpeg); empty: no logo.
    const QByteArray &logo() const { return m_logo; }
    QString logoMimeType() const { return m_logoMime; }

private:
    void apply(const QString &folder, bool isDefault);

    QString m_labName;
    QString m_title;
    QString m_language;
    QMap<QString, QString> m_headings;
    QByteArray m_logo;
    QString m_logoMime;
};

} // namespace driftlab
