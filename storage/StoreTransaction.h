#pragma once
// One transaction of a SessionStore for the length of a block (RAII): begins on construction,
// rolls back when the block is left without commit() (an exception, an early return), so a
// writer never leaves a transaction open or writes begin/try/rollback by hand.
//
//     StoreTransaction tx(store);
//     store.addEvent(...);  // throws: rolled back
//     tx.commit();

namespace driftlab {

class SessionStore;

class StoreTransaction {
public:
    explicit StoreTransaction(SessionStore &store); // SessionStore::begin(); throws StorageError
    ~StoreTransaction();                            // rollback() unless committed or rolled back
    StoreTransaction(const StoreTransaction &) = delete;
    StoreTransaction &operator=(const StoreTransaction &) = delete;

    void commit();   // SessionStore::commit(); a failed commit is rolled back and throws
    void rollback(); // ends it now, nothing written

private:
    SessionStore &m_store;
    bool m_open = true;
};

} // namespace driftlab
