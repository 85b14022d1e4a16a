#pragma once
#include "CliCommand.h"

#include <QList>

namespace driftlab {

class SessionStore;

// driftlab-cli fit SESSION... --model auto|mean|mlr|ridge|lagridge|exp|synthetic|dynamic
// --target CHANNEL [--points auto|ID,ID] [--drive CHANNEL|none] [--reference auto|absolute|
// start|start:MIN] [--train-range H:H] [--holdout SESSION... | --holdout-range H:H]
// [--k-range K:K] [--folds N] --out MODEL.json [--json FILE|-] [--db DB]:
// the data-driven path of `fit` (FitCommand hands over when --model names a data-driven model).
class DataDrivenFitCommand : public CliCommand {
public:
    QString name() const override { return QStringLiteral("fit"); }
    QString summary() const override;
    int run(const QStringList &args) override;

    // True when args hold --model NAME (or --model=NAME) with a data-driven model name.
    static bool handles(const QStringList &args);
    // A session argument (id or UUID) that exists in the store; SessionArgument::one.
    static qint64 sessionArg(const SessionStore &store, const QString &text, const QString &what, const QString &command);
    // Session ids from arguments that are ids, comma lists, UUIDs or ranges A:B (each must exist; SessionArgument).
    static QList<qint64> sessionArgs(const SessionStore &store, const QStringList &texts, const QString &what,
                                     const QString &command);
    // "K:K" for --k-range; UsageError otherwise.
    static void parseKRange(const QString &text, int &kMin, int &kMax, const QString &command);
};

} // namespace driftlab
