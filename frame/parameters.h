#pragma once
// A method's parameters (docs/adding-a-method.md): declared once, in the method's constructor,
// with their type, range, default and description, and read back through typed handles, so a
// value is never looked up by name where it is used (pbrt's ParameterDictionary read into
// typed members, Mitsuba's Properties). By name they are only set (from `--set name=value`,
// experiment files, the viewer) and listed (`shaftlab methods`, docs/methods.md, result rows).
//   integer, real  a number in [min, max];
//   boolean        true or false (also written on and off, or 1 and 0);
//   choice         one of `choices`, set and written by its name; read as the enum whose
//                  values follow the order of `choices`.

#include <cstddef>
#include <string>
#include <vector>

#include "core/check.h"

namespace sl::frame {

struct Parameter {
    enum class Type { integer, real, boolean, choice };
    std::string name;
    Type type = Type::real;
    double value = 0.0;
    double default_value = 0.0;
    double min = 0.0;
    double max = 0.0;
    std::string description{};
    std::vector<std::string> choices{};

    // The value as text: a number, true or false, or the chosen name.
    std::string text() const;
    // The type's name as `shaftlab methods` prints it: integer, real, bool or enum.
    const char* type_name() const;
};

// A typed handle to one declared parameter: *handle is its current value. Handles stay valid
// for the life of the set that declared them (which never moves: methods live on the heap).
template <class T>
class Param {
public:
    Param() = default;
    T operator*() const;
    const Parameter& declared() const {
        SL_DCHECK(all_ != nullptr);  // a handle the method never declared
        SL_DCHECK_INDEX(index_, all_->size());
        return (*all_)[index_];
    }
    explicit operator bool() const { return all_ != nullptr; }

private:
    friend class ParameterSet;
    Param(const std::vector<Parameter>* all, size_t index) : all_(all), index_(index) {}
    const std::vector<Parameter>* all_ = nullptr;
    size_t index_ = 0;
};

template <>
inline int Param<int>::operator*() const {
    return int(declared().value);
}
template <>
inline double Param<double>::operator*() const {
    return declared().value;
}
template <>
inline bool Param<bool>::operator*() const {
    return declared().value != 0.0;
}
template <class T>
T Param<T>::operator*() const {
    static_assert(std::is_enum_v<T>, "a choice is read as an enum");
    return T(int(declared().value));
}

// The parameters of one method, in the order declared. `owner` names the method in errors.
class ParameterSet {
public:
    explicit ParameterSet(std::string owner) : owner_(std::move(owner)) {}
    ParameterSet(const ParameterSet&) = delete;
    ParameterSet& operator=(const ParameterSet&) = delete;

    Param<int> integer(std::string name, int default_value, int min, int max,
                       std::string description);
    Param<double> real(std::string name, double default_value, double min, double max,
                       std::string description);
    Param<bool> flag(std::string name, bool default_value, std::string description);
    // `choices` name the enum's values in order; `default_value` is one of them.
    template <class Enum>
    Param<Enum> choice(std::string name, std::vector<std::string> choices, Enum default_value,
                       std::string description) {
        const size_t index = add_choice(std::move(name), std::move(choices), size_t(default_value),
                                        std::move(description));
        return Param<Enum>(&all_, index);
    }

    const std::vector<Parameter>& all() const { return all_; }
    bool has(const std::string& name) const;
    // The parameter as declared, with its current value; throws sl::Error naming the known ones
    // (and the nearest, when the name looks misspelt).
    const Parameter& find(const std::string& name) const;
    // Parses and sets one parameter; throws sl::Error naming the method and the parameter when
    // the name is unknown, the text is not a value of its type, or it is out of range.
    void set(const std::string& name, const std::string& text);

private:
    size_t add(Parameter parameter);
    size_t add_choice(std::string name, std::vector<std::string> choices, size_t default_index,
                      std::string description);

    std::string owner_;
    std::vector<Parameter> all_;
};

}  // namespace sl::frame
