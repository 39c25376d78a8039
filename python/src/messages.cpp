// SPDX-License-Identifier: Apache-2.0
// The protocol's messages the SDK takes and gives as they are (palp/probe.hpp): Params,
// Calibration, the program structs and ProgramStatus. Bound from the catalogue's own field lists
// (protocol/include/palp/protocol/catalogue.hpp), so a field added there appears here: every field
// is an attribute with its catalogue name (units in the names), enums are their names as str,
// arrays and tables are lists. Each class takes its fields as keyword arguments (the others keep
// the catalogue's defaults) and has to_dict() and ==.
#include <charconv>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <type_traits>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "palp/probe.hpp"

namespace palp_python {

namespace {

namespace proto = palp::proto;

template <class T>
py::object field_to_python(const T& v) {
  if constexpr (std::is_enum_v<T>) {
    return py::str(enum_text(v));
  } else if constexpr (requires { v.bytes; }) {
    std::string s(v.bytes.data(), v.bytes.size());
    return py::str(s.substr(0, s.find('\0')));
  } else if constexpr (requires { v.items; }) {
    py::list out;
    for (const auto& x : v) out.append(field_to_python(x));
    return out;
  } else if constexpr (requires { v.size(); }) {
    py::list out;
    for (const auto& x : v) out.append(field_to_python(x));
    return out;
  } else if constexpr (std::is_same_v<T, float>) {
    // the shortest decimal that reads back to the same f32 (0.01, not 0.009999999776482582)
    char text[32];
    const auto r = std::to_chars(text, text + sizeof text, v);
    return py::float_(std::strtod(std::string(text, r.ptr).c_str(), nullptr));
  } else {
    return py::cast(v);
  }
}

template <class T>
void field_from_python(py::handle o, T& out, const std::string& name) {
  if constexpr (std::is_enum_v<T>) {
    out = enum_of<T>(py::cast<std::string>(py::str(o)), name.c_str());
  } else if constexpr (requires { out.bytes; }) {
    out.assign(py::cast<std::string>(o).c_str());
  } else if constexpr (requires { out.items; }) {
    const auto seq = py::cast<py::sequence>(o);
    if (seq.size() > out.capacity)
      throw palp::ConfigError(name + ": at most " + std::to_string(out.capacity) + " values, got " +
                              std::to_string(seq.size()));
    out.size = 0;
    for (auto x : seq) field_from_python(x, out.items[out.size++], name);
  } else if constexpr (requires { out.size(); }) {
    const auto seq = py::cast<py::sequence>(o);
    if (seq.size() != out.size())
      throw palp::ConfigError(name + ": exactly " + std::to_string(out.size()) + " values, got " +
                              std::to_string(seq.size()));
    std::size_t k = 0;
    for (auto x : seq) field_from_python(x, out[k++], name);
  } else if constexpr (std::is_floating_point_v<T>) {
    out = static_cast<T>(py::cast<double>(o));
  } else {
    // integers: a float with a fraction or a value out of the field's range is refused
    const auto v = py::cast<long long>(py::module_::import("operator").attr("index")(o));
    if (v < static_cast<long long>(std::numeric_limits<T>::min()) ||
        static_cast<unsigned long long>(v) > static_cast<unsigned long long>(std::numeric_limits<T>::max()))
      throw palp::ConfigError(name + ": " + std::to_string(v) + " is out of the field's range");
    out = static_cast<T>(v);
  }
}

template <class M>
struct Fields {
  std::vector<std::string> names;
  std::map<std::string, std::function<void(M&, py::handle)>> setters;
  std::map<std::string, std::function<py::object(const M&)>> getters;
};

template <class M>
Fields<M>& fields() {
  static Fields<M> f;
  return f;
}

#define PALP_PY_FIELD(kind, type, n, name, since, def, lo, hi, unit, doc)                          \
  fields<M>().names.push_back(#name);                                                              \
  fields<M>().getters[#name] = [](const M& msg) { return field_to_python(msg.name); };            \
  fields<M>().setters[#name] = [](M& msg, py::handle v) { field_from_python(v, msg.name, #name); }; \
  cls.def_property(                                                                                \
      #name, [](const M& msg) { return field_to_python(msg.name); },                               \
      [](M& msg, py::handle v) { field_from_python(v, msg.name, #name); }, doc);

template <class M>
void finish_class(py::class_<M>& cls, const char* py_name) {
  cls.def(py::init([](const py::kwargs& kw) {
    M m{};
    for (auto item : kw) {
      const auto key = py::cast<std::string>(item.first);
      const auto it = fields<M>().setters.find(key);
      if (it == fields<M>().setters.end())
        throw palp::ConfigError(std::string(M::kName) + " has no field \"" + key + "\"");
      it->second(m, item.second);
    }
    return m;
  }));
  cls.def("to_dict", [](const M& m) {
    py::dict d;
    for (const auto& n : fields<M>().names) d[py::str(n)] = fields<M>().getters[n](m);
    return d;
  }, "Every field by its catalogue name.");
  cls.def("__eq__", [](const M& a, const M& b) { return a == b; }, py::is_operator());
  cls.def("__repr__", [py_name](const M& m) {
    std::string s = std::string(py_name) + "(";
    bool first = true;
    for (const auto& n : fields<M>().names) {
      s += (first ? "" : ", ") + n + "=" + py::cast<std::string>(py::repr(fields<M>().getters[n](m)));
      first = false;
    }
    return s + ")";
  });
  cls.attr("fields") = py::tuple(py::cast(fields<M>().names));
}

#define PALP_PY_MESSAGE(Message, py_name, doc)      \
  {                                                 \
    using M = proto::Message;                       \
    py::class_<M> cls(m, py_name, doc);             \
    PALP_FIELDS_##Message(PALP_PY_FIELD)            \
    finish_class(cls, py_name);                              \
  }

}  // namespace

void bind_messages(py::module_& m) {
  PALP_PY_MESSAGE(Params, "Params", "The device's parameters (Probe.params / set_params).")
  PALP_PY_MESSAGE(Calibration, "Calibration", "The device's calibration (Probe.calibration / set_calibration).")
  PALP_PY_MESSAGE(LoadHold, "HoldProgram", "Hold a current (Probe.load / run).")
  PALP_PY_MESSAGE(LoadRamp, "RampProgram", "Staircase ramp of the current.")
  PALP_PY_MESSAGE(LoadSine, "SineProgram", "Sinusoidal current.")
  PALP_PY_MESSAGE(LoadSweep, "SweepProgram", "Stepped-sine sweep.")
  PALP_PY_MESSAGE(LoadMultisine, "MultisineProgram", "Multisine excitation.")
  PALP_PY_MESSAGE(LoadContactWatch, "ContactWatchProgram", "Hold a current and watch for contact.")
  PALP_PY_MESSAGE(ProgramStatus, "ProgramStatus", "The program's state (Probe.program_status).")
}

}  // namespace palp_python
