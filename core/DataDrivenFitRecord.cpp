#include "DataDrivenFitRecord.h"

#include "DataDrivenFit.h"
#include "DataDrivenModelJson.h"
#include "SessionStore.h"

#include <QFileInfo>

#include <stdexcept>

namespace driftlab {

QString DataDrivenFitRecord::software(Face face)
{
    return (face == Face::Cli ? QStringLiteral("driftlab-cli ") : QStringLiteral("driftlab-gui ")) +
           QStringLiteral(DRIFTLAB_VERSION);
}

FittedModel DataDrivenFitRecord::record(const DataDrivenFitResult &result, const QJsonObject &document, Face face,
                                        const QString &file)
{
    FittedModel fm;
    fm.model = QStringLiteral("driftlab-model/%1").arg(QString::fromStdString(result.model.kind));
    fm.parameters = DataDrivenModelJson::toJson(result.model);
    fm.uncertainties = document.value(QStringLiteral("uncertainties")).toObject();
    fm.provenance = QJsonObject{{QStringLiteral("training"), document.value(QStringLiteral("training"))},
                                {QStringLiteral("hyperparameters"), document.value(QStringLiteral("hyperparameters"))},
                                {QStringLiteral("software"), software(face)}};
    if (document.contains(QStringLiteral("model_selection")))
        fm.provenance.insert(QStringLiteral("model_selection"), document.value(QStringLiteral("model_selection")));
    if (!file.isEmpty())
        fm.provenance.insert(QStringLiteral("file"), QFileInfo(file).absoluteFilePath());
    fm.metrics = document.value(QStringLiteral("metrics")).toObject();
    return fm;
}

qint64 DataDrivenFitRecord::store(SessionStore &store, const DataDrivenFitResult &result, const QJsonObject &document, Face face,
                                  const QString &file)
{
    const QJsonObject training = document.value(QStringLiteral("training")).toObject();
    const qint64 session = training.value(QStringLiteral("session")).toVariant().toLongLong();
    if (session <= 0)
        throw std::invalid_argument("the fitted model names no training session");
    return store.addFittedModel(session, record(result, document, face, file));
}

} // namespace driftlab
