#pragma once
// Test helper: evaluates the arithmetic the controller exporters write (840D synchronized
// actions, Fanuc macro B, Heidenhain TEMPCOMP): numbers, named variables (matched literally,
// longest first, e.g. "$R[100]", "#500", "W486"), + - * /, unary minus, ( ) or [ ] grouping
// and EXP. Independent of the exporters' own code; throws std::runtime_error on anything else.

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>

namespace driftlab::test {

class FormulaEvaluator {
public:
    explicit FormulaEvaluator(std::map<std::string, double> variables) : m_vars(std::move(variables)) {}

    double evaluate(const std::string &text)
    {
        m_s = text;
        m_i = 0;
        const double v = sum();
        skip();
        if (m_i != m_s.size())
            throw std::runtime_error("unexpected '" + m_s.substr(m_i) + "' in " + m_s);
        return v;
    }

private:
    void skip()
    {
        while (m_i < m_s.size() && std::isspace(static_cast<unsigned char>(m_s[m_i])))
            ++m_i;
    }
    bool take(char c)
    {
        skip();
        if (m_i < m_s.size() && m_s[m_i] == c) {
            ++m_i;
            return true;
        }
        return false;
    }
    double sum()
    {
        double v = product();
        for (;;) {
            if (take('+'))
                v += product();
            else if (take('-'))
                v -= product();
            else
                return v;
        }
    }
    double product()
    {
        double v = unary();
        for (;;) {
            if (take('*'))
                v *= unary();
            else if (take('/'))
                v /= unary();
            else
                return v;
        }
    }
    double unary()
    {
        if (take('-'))
            return -unary();
        return primary();
    }
    double group(char open)
    {
        const char close = open == '(' ? ')' : ']';
        const double v = sum();
        if (!take(close))
            throw std::runtime_error(std::string("missing '") + close + "' in " + m_s);
        return v;
    }
    double primary()
    {
        skip();
        // Longest variable name first ("$R[100]" before a '[' group).
        std::string best;
        for (const auto &kv : m_vars)
            if (m_s.compare(m_i, kv.first.size(), kv.first) == 0 && kv.first.size() > best.size())
                best = kv.first;
        if (!best.empty()) {
            m_i += best.size();
            return m_vars.at(best);
        }
        if (take('('))
            return group('(');
        if (take('['))
            return group('[');
        if (m_s.compare(m_i, 3, "EXP") == 0) {
            m_i += 3;
            skip();
            if (take('('))
                return std::exp(group('('));
            if (take('['))
                return std::exp(group('['));
            throw std::runtime_error("EXP without argument in " + m_s);
        }
        const char *start = m_s.c_str() + m_i;
        char *end = nullptr;
        const double v = std::strtod(start, &end);
        if (end == start)
            throw std::runtime_error("cannot read '" + m_s.substr(m_i) + "' in " + m_s);
        m_i += static_cast<std::size_t>(end - start);
        return v;
    }

    std::map<std::string, double> m_vars;
    std::string m_s;
    std::size_t m_i = 0;
};

} // namespace driftlab::test
