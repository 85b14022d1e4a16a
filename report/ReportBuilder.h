#pragma once
// Collects the test report of one stored session: metadata and sensor table, the seed-002
// figure set (thermal error against time and position, error surface, temperatures against
// time, infrared temperature against position and time, infrared profile), ISO 230-2 values
// per interferometer test and the ISO 230-3 drift summary (ReportIso230Section), the stored sensitive-point
// selection, the fitted models stored with the session (parameters, uncertainties, metrics,
// validation figure), the stored diagnosis and the compensation results. Every section whose
// data the session lacks is left out with one line saying why and how to produce it.
//
// Figures come from the same plot classes the GUI and `driftlab-cli plot` use, drawn as SVG.
// Needs a QApplication (plots are widgets); no display.

#include "ReportDocument.h"

#include <QSizeF>
#include <QString>

#include <functional>

class QwtPlot;

namespace driftlab {

class ReportTemplate;
struct FittedModel;
class SessionStore;

class ReportBuilder {
public:
    using Progress = std::function<void(const QString &stage)>;

    // Throws StorageError if the session does not exist.
    ReportBuilder(const SessionStore &store, qint64 sessionId, const ReportTemplate &look);
    ReportDocument build(const Progress &progress = {}) const;

    // A plot drawn into SVG at size_mm (text stays text, curves stay paths).
    static QByteArray svg(QwtPlot &plot, QSizeF size_mm);
    // A figure's size on paper (the width of an A4 text column).
    static constexpr QSizeF kFigure_mm{174, 100};

private:
    void sessionSection(ReportDocument &doc) const;
    void figureSection(ReportDocument &doc) const;
    void sensitivePointSection(ReportDocument &doc) const;
    void modelSection(ReportDocument &doc) const;
    void fdmSection(ReportDocument &doc, const FittedModel &model) const;
    void dataDrivenChoice(ReportDocument &doc, const FittedModel &model) const;
    void fdmFigure(ReportDocument &doc, const FittedModel &model) const;
    void diagnosisSection(ReportDocument &doc) const;
    void compensationSection(ReportDocument &doc) const;

    const SessionStore &m_store;
    qint64 m_session;
    const ReportTemplate &m_look;
};

} // namespace driftlab
