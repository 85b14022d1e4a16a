#include "ReportDocument.h"

#include "ElapsedTimeAxis.h"

#include <cmath>

namespace driftlab {

QString ReportDocument::number(double v, int digits)
{
    return std::isfinite(v) ? QString::number(v, 'g', digits) : QStringLiteral("-");
}

QString ReportDocument::elapsed(double t_s)
{
    return std::isfinite(t_s) ? ElapsedTimeAxis::format(t_s) : QStringLiteral("-");
}

void ReportDocument::paragraph(const QString &plainText)
{
    html(QStringLiteral("<p>%1</p>").arg(plainText.toHtmlEscaped()));
}

void ReportDocument::table(const QStringList &header, const QVector<QStringList> &rows, int rowsPerBlock)
{
    QString head = QStringLiteral("<tr>");
    for (const QString &h : header)
        head += QStringLiteral("<th>%1</th>").arg(h.toHtmlEscaped());
    head += QStringLiteral("</tr>");
    for (int first = 0; first < rows.size() || first == 0; first += rowsPerBlock) {
        QString t = QStringLiteral("<table width=\"100%\" cellspacing=\"0\" cellpadding=\"3\">") + head;
        for (int r = first; r < std::min<int>(rows.size(), first + rowsPerBlock); ++r) {
            t += QStringLiteral("<tr>");
            for (const QString &cell : rows[r])
                t += QStringLiteral("<td>%1</td>").arg(cell.toHtmlEscaped());
            t += QStringLiteral("</tr>");
        }
        html(t + QStringLiteral("</table>"));
        if (rows.isEmpty())
            break;
    }
}

void ReportDocument::keyValues(const QVector<QPair<QString, QString>> &pairs)
{
    QString t = QStringLiteral("<table class=\"kv\" cellspacing=\"0\" cellpadding=\"3\">");
    for (const auto &p : pairs)
        t += QStringLiteral("<tr><th>%1</th><td>%2</td></tr>").arg(p.first.toHtmlEscaped(), p.second.toHtmlEscaped());
    html(t + QStringLiteral("</table>"));
}

} // namespace driftlab
