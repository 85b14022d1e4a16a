#pragma once
// What the central area shows while the open database has no session (or none is open):
// the three ways to begin (issue 33): record a simulated session, open the example
// bundle, import a CSV table. MainWindow carries them out.

#include <QWidget>

class QLabel;
class QPushButton;

namespace driftlab {

class WelcomePage : public QWidget {
    Q_OBJECT
public:
    explicit WelcomePage(QWidget *parent = nullptr);
    // Names the database the first session will go into.
    void setDatabase(const QString &path);
    QPushButton *recordButton() const { return m_record; }
    QPushButton *exampleButton() const { return m_example; }
    QPushButton *csvButton() const { return m_csv; }

signals:
    void recordSimulated();
    void openExample();
    void importCsv();

private:
    QLabel *m_database;
    QPushButton *m_record;
    QPushButton *m_example;
    QPushButton *m_csv;
};

} // namespace driftlab
