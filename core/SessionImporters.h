#pragma once
// The importers ImporterRegistry holds, one function each, defined in the file of its format:
// a recording bundle (BundleSessionImporter.cpp: NAME.bundle folder with manifest.json, or
// .zip; BundleTransfer), a session database (SqliteSessionImporter.cpp: its sessions copied,
// SessionCopier), the interferometer runs of a Renishaw .rtl file added to a session
// (RtlSessionImporter.cpp; InterferometerImport), a CSV table with a column map
// (CsvSessionImporter.cpp; CsvImporter, one session per run).

#include "SessionImporter.h"

namespace driftlab {

SessionImporter bundleSessionImporter();
SessionImporter sqliteSessionImporter();
SessionImporter rtlSessionImporter();
SessionImporter csvSessionImporter();

} // namespace driftlab
