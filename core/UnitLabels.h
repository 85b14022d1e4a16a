#pragma once
// One notation for units wherever a person reads them (the GUI, the report, CLI messages,
// stored session events): the stored ASCII unit codes (degC, um, mm/min, W/(m^2 K)) shown as
// °C, µm, mm/min, W/(m² K). The codes themselves stay ASCII in storage, JSON and CSV headers
// (docs/glossary.md). In core/ (QtCore only) so core/'s events and app/cli reach it too.

#include <QString>

#include <optional>

namespace driftlab {

class UnitLabels {
public:
    static QString display(const QString &unit);
    // The same inside prose from analysis/ (explanations, evidence, location summaries): the
    // words um and degC become µm and °C ("0.68 um", "2.7 um/K", "1.2 degC").
    static QString inText(const QString &text);
    // One name per quantity on screen (issue 33): a channel kind as axes and tables say it.
    // A probe's "displacement" is the screw's elongation; the interferometer's deviation at a
    // target is the thermal error. Other kinds as they are.
    static QString quantity(const QString &kind);
    // A session's stored start (ISO 8601, "2026-11-27T19:33:28Z") as every screen shows it:
    // "2026-11-27 19:33" in UTC; text that is not a date as it is.
    static QString startTime(const QString &iso);
    // Elapsed time in whole seconds (floored; below zero as 0) as h:mm:ss, as the CLI and the
    // ISO 230 summary print it (the plots' axes: widgets/ElapsedTimeAxis).
    static QString clock(double seconds);
    // The inverse, for every place a person types an elapsed time or a duration (the CLI's
    // --duration/--from/--to, the Analysis dock's ranges, the Acquisition dock's duration, the
    // measurement run's times): "H:MM:SS" or "M:SS" (minutes and seconds below 60), plain
    // seconds, or a number with a unit ("2 h", "90 min", "45 s"; a decimal comma is read as a
    // point). Fractions are allowed on the last field. Not negative. nullopt with *why ("'ten'
    // is not a duration (SECONDS or H:MM:SS)", "'1:99:00': minutes must be below 60 in
    // H:MM:SS") when it is not one.
    static std::optional<double> parseClock(const QString &text, QString *why = nullptr);
};

} // namespace driftlab
