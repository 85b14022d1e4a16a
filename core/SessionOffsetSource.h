#pragma once
// The offset a live compensation loop writes, from a fitted data-driven model following a
// session as it is recorded: each update() reads the samples the model's input channels gained
// since the last one (its own read-only connection to the session's database, opened on the
// calling thread), advances the model on the first input's sample times with the other inputs
// held at their latest value (as the fitters' grid does), and returns the compensation -E in um
// at the newest time every input has reached. The synthetic model is evaluated at the latest
// position of its position channel. A physics model (fdm-seed000) reads the session's channels
// by role (axis_position, feed_rate, ambient; the position drives the schedule) and advances the
// explicit FdmScrewModel in whole steps of its grid dt up to each position sample, exactly as
// the exported C code's step() does; E is the thermal error at the latest axis position.

#include "DataDrivenPredictor.h"
#include "ExportableModel.h"
#include "FdmScrewModel.h"

#include <QString>
#include <QVector>

#include <cmath>
#include <memory>
#include <optional>

namespace driftlab {

class SessionStore;

class SessionOffsetSource {
public:
    // Checks what can be checked without the database: the model kind. Throws
    // std::invalid_argument with the reason.
    SessionOffsetSource(const QString &databasePath, qint64 sessionId, const ExportableModel &model,
                        const QString &positionChannel = QStringLiteral("X"));
    ~SessionOffsetSource();

    // Throws std::invalid_argument naming the channel when the session lacks an input of the
    // model, StorageError when the database cannot be read; opens (and closes) its own
    // connection on the calling thread, so a command can refuse before any work.
    void checkInputs() const;
    // Throws std::invalid_argument when the session lacks an input channel, StorageError when
    // the database cannot be read. NaN until every input has a sample.
    double update();
    // The compensation -E at another axis position, at the model time of the last update() (for
    // the support points of a live compensation table): the physics and synthetic models are
    // position-dependent, the others give the same value everywhere. NaN before the first.
    double offsetAt(double position_mm) const;
    double modelTime_s() const { return m_time_s > -1e299 ? m_time_s : std::nan(""); } // NaN before the first step
    double error_um() const { return m_error_um; } // the model's E at modelTime_s
    // The stated 1-sigma uncertainty of error_um() (um) of the model in use; NaN when unknown.
    double sigma_um() const;

    // Live robustness (data-driven models): an input is failed at model time t when its newest
    // sample is older than t - staleLimit_s (silent) or its value, as the model reads it, is
    // outside its training range by more than DataDrivenModel::extrapolationMargin. Then the
    // source uses the reduced model without that input (fitted and stored with the model, run
    // alongside from the start so its lags are warm); with no such model (two inputs failed, or
    // none stored) it holds the last offset of a model whose inputs were all sound. It goes back
    // to the full model when the input recovers. Each switch is an event (takeEvents()).
    void setStaleLimit(double seconds) { m_stale_s = seconds; }
    // "full", "without T3" or "holding"
    QString mode() const;
    // The switches since the last call, at model time t (session seconds): "input 'T3' silent
    // since 03:10:00 (session time): using the model without T3", "... holding -12.4 um",
    // "input 'T3' back: using the full model".
    struct Event {
        double t_s = 0.0;
        QString text;
    };
    QVector<Event> takeEvents();

private:
    struct Reduced {
        DataDrivenModel model;
        std::optional<DataDrivenPredictor> predictor;
        std::vector<int> map;    // per reduced input: index into the full model's inputs
        std::vector<double> held;
        int without = -1;        // the full model's input it does without
        double error_um = 0.0;
        bool started = false;
    };
    void open();
    void stepReduced(Reduced &r, double t);
    QString failure(int input, double t) const; // why input is failed at t ("" = sound)
    void choose(double t);
    double m_stale_s = 30.0;
    std::vector<Reduced> m_reduced;
    std::vector<double> m_heldT;       // per input: time of the held value
    int m_active = -1;                 // -1 full model, >= 0 index into m_reduced, -2 holding
    int m_failedInput = -1;
    double m_safe_um = 0.0;            // last E of a model whose inputs were sound
    double m_sigma_um = std::nan("");
    QVector<Event> m_events;
    QVector<qint64> resolveInputs(SessionStore &store, qint64 *positionId) const;

    QString m_path;
    qint64 m_session;
    void stepTo(double t);

    ExportableModel m_exportable;
    DataDrivenModel m_model;
    std::optional<FdmScrewModel> m_fdm;
    double m_fdmStart_s = 0.0;
    long long m_fdmSteps = 0;
    QString m_positionChannel;
    std::unique_ptr<SessionStore> m_store;
    std::optional<DataDrivenPredictor> m_predictor;
    QVector<qint64> m_channels;        // per model input
    qint64 m_positionId = 0;
    QVector<double> m_readUpTo;        // per input: newest sample time read
    QVector<QVector<double>> m_pendT, m_pendV; // per input: samples read but not yet consumed
    std::vector<double> m_held;        // per input: latest value at the model time
    double m_position_mm = 0.0;
    double m_time_s = -1e300;
    double m_error_um = 0.0;
};

} // namespace driftlab
