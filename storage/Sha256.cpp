#include "Sha256.h"

#include <openssl/evp.h>

#include <stdexcept>

namespace driftlab {

struct Sha256::Context {
    EVP_MD_CTX *ctx = EVP_MD_CTX_new();
    ~Context() { EVP_MD_CTX_free(ctx); }
};

Sha256::Sha256() : m_ctx(std::make_unique<Context>())
{
    if (!m_ctx->ctx || EVP_DigestInit_ex(m_ctx->ctx, EVP_sha256(), nullptr) != 1)
        throw std::runtime_error("SHA-256: libcrypto could not start a digest");
}

Sha256::~Sha256() = default;

void Sha256::add(const void *data, size_t size)
{
    if (size > 0 && EVP_DigestUpdate(m_ctx->ctx, data, size) != 1)
        throw std::runtime_error("SHA-256: libcrypto could not add data");
}

QByteArray Sha256::result()
{
    unsigned char md[EVP_MAX_MD_SIZE];
    unsigned int n = 0;
    if (EVP_DigestFinal_ex(m_ctx->ctx, md, &n) != 1)
        throw std::runtime_error("SHA-256: libcrypto could not finish a digest");
    return QByteArray(reinterpret_cast<const char *>(md), static_cast<int>(n));
}

QByteArray Sha256::of(const QByteArray &bytes)
{
    Sha256 h;
    h.add(bytes);
    return h.result();
}

} // namespace driftlab
