#include "RequestError.h"

namespace driftlab {

RequestError::RequestError(const QString &cli, const QString &onScreen)
    : std::invalid_argument(cli.toStdString()), m_onScreen(onScreen)
{
}

QString RequestError::forScreen(const std::exception &e)
{
    if (const auto *r = dynamic_cast<const RequestError *>(&e))
        return r->onScreen();
    return QString::fromUtf8(e.what());
}

} // namespace driftlab
