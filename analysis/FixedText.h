#pragma once
// A number in fixed notation with `precision` decimals, for evidence and explanations in words.

#include <sstream>
#include <string>

namespace driftlab {

inline std::string fixedText(double v, int precision)
{
    std::ostringstream o;
    o.setf(std::ios::fixed);
    o.precision(precision);
    o << v;
    return o.str();
}

} // namespace driftlab
