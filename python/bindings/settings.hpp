#pragma once
// Settings and results at the Python boundary (docs/design.md, "Settings and results").
//
// Every C++ settings struct is bound once, by SettingsClass<T>: a class whose defaults are those of the
// default-constructed struct, with a keyword constructor, one read-write attribute per field (its unit
// in the doc), __repr__, ==, copy and pickling. Functions that take settings accept `settings=` (an
// instance) plus keyword overrides of its fields, merged by settings_from<T>; so the old keyword calls
// keep working and no binding restates a default number. settings_doc<T>() lists the fields, with the
// struct's defaults, for those functions' docstrings.
//
// Settings classes get no public methods: Python code lists their fields as the public names of the
// class (graspmix.sim.make_settings). The field names are in the class attribute `_fields`.
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "common.hpp"

namespace graspmix::py_bind {

struct SettingsField {
  std::string name, doc;
};

/// The Python name and the fields of a bound settings struct T.
template <class T>
struct SettingsInfo {
  static std::string& name() {
    static std::string n;
    return n;
  }
  static std::vector<SettingsField>& fields() {
    static std::vector<SettingsField> f;
    return f;
  }
  static bool has(const std::string& field) {
    for (const auto& f : fields())
      if (f.name == field) return true;
    return false;
  }
  static std::string names() {
    std::string out;
    for (const auto& f : fields()) out += (out.empty() ? "" : ", ") + f.name;
    return out;
  }
};

/// What a settings field holding `value` takes, in words (for the message of a value of the wrong type).
inline std::string kind_of(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return "true or false";
  if (py::isinstance<py::int_>(value)) return "an integer";
  if (py::isinstance<py::float_>(value)) return "a number";
  if (py::isinstance<py::str>(value)) return "text";
  if (py::hasattr(value, "_fields")) return "a " + std::string(py::str(py::type::of(value).attr("__name__")));
  return "a value like " + std::string(py::repr(value)).substr(0, 40);
}

/// What a settings field of C++ type D takes, in words.
template <class D>
std::string expected_kind() {
  if constexpr (std::is_same_v<D, bool>) {
    return "true or false";
  } else if constexpr (std::is_integral_v<D>) {
    return "an integer in [" + std::to_string(std::numeric_limits<D>::min()) + ", " +
           std::to_string(std::numeric_limits<D>::max()) + "]";
  } else if constexpr (std::is_floating_point_v<D>) {
    return "a number";
  } else if constexpr (std::is_same_v<D, std::string>) {
    return "text";
  } else {
    return "a " + std::string(py::str(py::type::of<D>().attr("__name__")));
  }
}

/// Whether `value` is of a kind a field of C++ type D takes, before pybind11 converts it: a bool field takes true
/// or false (numpy's too) and the integers 0 and 1, not None or any number (pybind11 takes both); a number
/// field takes no bool (pybind11 would take it as 0 or 1).
template <class D>
bool is_kind_of(const py::handle& value) {
  if constexpr (std::is_same_v<D, bool>) {
    if (py::isinstance<py::bool_>(value) || py::isinstance(value, py::module_::import("numpy").attr("bool_"))) {
      return true;
    }
    return py::isinstance<py::int_>(value) && (value.equal(py::int_(0)) || value.equal(py::int_(1)));
  } else if constexpr (std::is_arithmetic_v<D>) {
    return !py::isinstance<py::bool_>(value);
  } else {
    return true;
  }
}

/// `value` as the C++ type D of the settings field `name`: what attribute assignment converts (an int or float
/// for a number, an int for an integer, a str for text; see is_kind_of). Anything else, an integer beyond D's
/// range included, is a ValueError naming the field, never pybind11's TypeError listing C++ signatures.
template <class D>
D setting_value(const py::handle& value, const std::string& name) {
  if (is_kind_of<D>(value)) {
    try {
      return value.cast<D>();
    } catch (const py::cast_error&) {
    }
  }
  throw py::value_error("setting '" + name + "': " + std::string(py::repr(value)).substr(0, 80) +
                        " is not valid: expected " + expected_kind<D>());
}

/// A copy of `settings` (an instance of T, or None for `base`, by default T's defaults) with the keyword
/// overrides applied through the bound attributes, so they convert exactly as attribute assignment
/// does. An unknown keyword is a ValueError naming it and listing the valid ones; `where` names the
/// caller in every message.
template <class T>
T settings_from(const py::handle& settings, const py::dict& overrides, const std::string& where, const T& base = T{}) {
  using Info = SettingsInfo<T>;
  T s = base;
  if (settings && !settings.is_none()) {
    if (!py::isinstance<T>(settings)) {
      throw py::value_error(where + ": settings must be a " + Info::name() + ", got " +
                            std::string(py::str(py::type::of(settings).attr("__name__"))));
    }
    s = settings.cast<T>();
  }
  if (overrides.empty()) return s;
  py::object obj = py::cast(s);
  for (const auto& item : overrides) {
    const std::string key = py::str(item.first);
    if (!Info::has(key)) {
      throw py::value_error(where + ": unknown setting '" + key + "' (valid: " + Info::names() + ")");
    }
    try {
      obj.attr(key.c_str()) = item.second;
    } catch (py::error_already_set& e) {
      if (!e.matches(PyExc_TypeError) && !e.matches(PyExc_ValueError)) throw;
      const std::string message = py::str(e.value());
      if (e.matches(PyExc_ValueError) && message.rfind("setting '" + key + "'", 0) == 0) {
        throw py::value_error(where + ": " + message);  // setting_value's, which names the field already
      }
      // pybind11's TypeError lists C++ signatures: say what the field takes instead.
      const std::string why = e.matches(PyExc_ValueError) ? message : "expected " + kind_of(obj.attr(key.c_str()));
      throw py::value_error(where + ": setting '" + key + "': " + std::string(py::repr(item.second)).substr(0, 80) +
                            " is not valid: " + why);
    }
  }
  return obj.cast<T>();
}

/// The docstring paragraph that lists T's fields with their defaults (from T{}) and docs.
template <class T>
std::string settings_doc(const T& defaults = T{}) {
  using Info = SettingsInfo<T>;
  const py::object d = py::cast(defaults);
  std::string out = "Settings: settings= a " + Info::name() +
                    " (None: its defaults), and/or its fields as keywords,\n"
                    "which override it (an unknown keyword is a ValueError):\n";
  for (const auto& f : Info::fields()) {
    out += "  " + f.name + " = " + std::string(py::repr(d.attr(f.name.c_str())));
    if (!f.doc.empty()) out += ": " + f.doc;
    out += "\n";
  }
  return out;
}

/// Binds a settings struct once; call field()/property() for every member, then done().
template <class T>
class SettingsClass {
 public:
  using Info = SettingsInfo<T>;

  SettingsClass(py::handle scope, const char* name, std::string doc) : cls_(scope, name), doc_(std::move(doc)) {
    Info::name() = name;
    Info::fields().clear();
    cls_.def(py::init<>(), "The defaults: those of the default-constructed C++ struct.");
  }

  /// A plain member; `doc` gives its unit. A value of the wrong type is a ValueError naming it (setting_value).
  template <class D>
  SettingsClass& field(const char* name, D T::* member, const char* doc = "") {
    // As def_readwrite (a nested settings object is returned by reference, so its attributes write through),
    // with the value converted by setting_value.
    const std::string field_name = name;
    const py::cpp_function get([member](const T& s) -> const D& { return s.*member; }, py::is_method(cls_));
    const py::cpp_function set(
        [member, field_name](T& s, const py::object& v) { s.*member = setting_value<D>(v, field_name); },
        py::is_method(cls_));
    cls_.def_property(name, get, set, py::return_value_policy::reference_internal, doc);
    Info::fields().push_back({name, doc});
    return *this;
  }

  /// A member with a converting getter and setter (vectors from any array-like, enums from strings...).
  template <class Get, class Set>
  SettingsClass& property(const char* name, Get&& get, Set&& set, const char* doc = "") {
    cls_.def_property(name, std::forward<Get>(get), std::forward<Set>(set), doc);
    Info::fields().push_back({name, doc});
    return *this;
  }

  /// A seed: a non-negative integer; None means 0 (graspmix never seeds from the clock).
  SettingsClass& seed(const char* name, std::uint64_t T::* member, const char* doc) {
    return property(
        name, [member](const T& s) { return s.*member; },
        [member](T& s, const py::object& v) { s.*member = to_seed(v); }, doc);
  }

  /// The keyword constructor, __repr__, ==, copy, pickling, `_fields` and the field list in the doc.
  py::class_<T>& done() {
    const std::string name = Info::name();
    cls_.def(
        py::init([name](const py::kwargs& kw) { return settings_from<T>(py::none(), kw, name); }),
        ("Keyword constructor: any of the fields (" + Info::names() + "); the others keep their defaults.").c_str());
    py::list names;
    for (const auto& f : Info::fields()) names.append(f.name);
    cls_.attr("_fields") = py::tuple(names);
    cls_.def("__repr__", [name](const py::object& self) {
      std::string out = name + "(";
      bool first = true;
      for (const auto& f : Info::fields()) {
        out += (first ? "" : ", ") + f.name + "=" + std::string(py::repr(self.attr(f.name.c_str())));
        first = false;
      }
      return out + ")";
    });
    cls_.def(
        "__eq__",
        [](const py::object& self, const py::object& other) -> py::object {
          if (!py::isinstance<T>(other)) return py::reinterpret_borrow<py::object>(Py_NotImplemented);
          const py::object ndarray = py::module_::import("numpy").attr("ndarray");
          const py::object array_equal = py::module_::import("numpy").attr("array_equal");
          for (const auto& f : Info::fields()) {
            const py::object a = self.attr(f.name.c_str()), b = other.attr(f.name.c_str());
            const bool same =
                py::isinstance(a, ndarray) || py::isinstance(b, ndarray) ? array_equal(a, b).cast<bool>() : a.equal(b);
            if (!same) return py::bool_(false);
          }
          return py::bool_(true);
        },
        py::is_operator());
    cls_.attr("__hash__") = py::none();
    cls_.def("__copy__", [](const T& s) { return T(s); });
    cls_.def("__deepcopy__", [](const T& s, const py::object&) { return T(s); }, py::arg("memo"));
    cls_.def(py::pickle(
        [](const py::object& self) {
          py::dict d;
          for (const auto& f : Info::fields()) d[py::str(f.name)] = self.attr(f.name.c_str());
          return d;
        },
        [name](const py::dict& d) { return settings_from<T>(py::none(), d, name); }));
    cls_.doc() = doc_ + "\n\n" + settings_doc<T>();
    return cls_;
  }

  py::class_<T>& cls() { return cls_; }

 private:
  py::class_<T> cls_;
  std::string doc_;
};

}  // namespace graspmix::py_bind
