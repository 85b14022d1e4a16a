#include "StoreTransaction.h"

#include "SessionStore.h"

namespace driftlab {

StoreTransaction::StoreTransaction(SessionStore &store) : m_store(store)
{
    m_store.begin();
}

StoreTransaction::~StoreTransaction()
{
    if (m_open)
        m_store.rollback(); // does not throw
}

void StoreTransaction::commit()
{
    m_open = false; // SessionStore::commit rolls back itself when it fails
    m_store.commit();
}

void StoreTransaction::rollback()
{
    m_open = false;
    m_store.rollback();
}

} // namespace driftlab
