#pragma once
// File > Export model to controller: pick a fitted model stored with the open database's
// sessions (listed, the current session's newest first) or, with Browse..., a MODEL.json (fit
// --json, fit --model ... --out, or the Analysis dock's "save MODEL.json"), a target from the export registry, axis and base
// name; the preview shows exactly the files that will be written (one tab each), the notes and
// the approximation error, or why the target refuses the model. Export writes them into a
// folder. Both steps are core/ModelExport's (prepare, write), as 'driftlab-cli export-model'
// runs them: the same request check, the same bytes, nothing left behind by a failed write.

#include "ModelExport.h"

#include <QJsonObject>
#include <QVector>

#include <QDialog>

class QComboBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QTabWidget;

namespace driftlab {

class SessionStore;

class ModelExportDialog : public QDialog {
    Q_OBJECT

public:
    explicit ModelExportDialog(QWidget *parent = nullptr);

    // Lists the models stored with the sessions of `store` (nullptr: none) and selects the
    // newest of `currentSession` (else the newest of all).
    void setStore(const SessionStore *store, qint64 currentSession = 0);
    // The listed stored models, as shown ("#3 X warm-up: fdm-seed000, 2026-11-20 08:14").
    QStringList storedModels() const;
    // Selects a listed model by index (-1: the file of the Model field).
    void selectStoredModel(int index);
    void setModelPath(const QString &path);
    void setTarget(const QString &name);
    void setAxis(const QString &axis); // X, Y or Z
    void setFolder(const QString &folder);
    // What the preview currently shows (for tests): file names and contents, or the error.
    QStringList previewFileNames() const;
    QString previewText(const QString &fileName) const;
    QString message() const;
    bool canExport() const;
    // Writes the previewed files into the folder; false (and message() says why) on failure.
    bool exportFiles();

private:
    void browseModel();
    void browseFolder();
    void refresh();

    ModelExport m_exporting;
    ModelExport::Result m_result;
    bool m_ok = false;
    QVector<ModelExport::StoredModel> m_stored;
    QComboBox *m_storedChoice = nullptr;
    QLineEdit *m_model = nullptr;
    QComboBox *m_target = nullptr;
    QComboBox *m_axis = nullptr;
    QLineEdit *m_name = nullptr;
    QLineEdit *m_folder = nullptr;
    QLabel *m_message = nullptr;
    QTabWidget *m_preview = nullptr;
    QPushButton *m_export = nullptr;
};

} // namespace driftlab
