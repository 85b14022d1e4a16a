#pragma once
// A refused request (bad usage or bad input, exit 2 in the CLI) that can be told in the words
// of either face: what() names the CLI's option and hours ("--train-range 0:2 and
// --holdout-range 1:3 overlap ..."), onScreen() the GUI's field and its h:mm:ss ("Training time
// 0:00:00 to 2:00:00 and held-out time ..."). A plain std::invalid_argument has one wording.

#include <QString>

#include <exception>
#include <stdexcept>

namespace driftlab {

class RequestError : public std::invalid_argument {
public:
    RequestError(const QString &cli, const QString &onScreen);

    QString onScreen() const { return m_onScreen; }

    // The message of `e` as the GUI shows it: onScreen() for a RequestError, else what().
    static QString forScreen(const std::exception &e);

private:
    QString m_onScreen;
};

} // namespace driftlab
