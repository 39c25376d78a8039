// SPDX-License-Identifier: Apache-2.0
// The Vega runtime of the self-contained page, from Debian 12's libjs-vega. Its browser files are
// one UMD file per module, and each, loaded as a plain script, replaces `window.vega` with its
// own exports: loading several naively leaves only the last. Each file calls
// define([deps...], factory) when a global AMD `define` exists, so the page first installs a
// small one: it records every file's factory under the module's name, and afterwards resolves
// the modules on demand (a module's factory runs once, after the modules it names), merges their
// exports into one `vega` object in the order vega's own index re-exports them, and registers
// the transforms in vega-dataflow's table (as that index, and host/report/vega-to-svg.js, do).
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include "format/text_input.hpp"
#include "palp/error.hpp"
#include "report/report_internal.hpp"

namespace palp::report::detail {

namespace fs = std::filesystem;

namespace {

struct ModuleFile {
  const char* name;     ///< the AMD module name the other files ask for
  const char* file;     ///< under the JavaScript directory
  const char* package;  ///< the Debian package that ships it
};

// What View, parse and the transforms need, in vega's index order (vega-functions asks for
// 'vega-selections', which Debian ships as vega-selection.js).
constexpr ModuleFile kModules[] = {
    {"topojson-client", "topojson-client/topojson-client.js", "libjs-vega"},
    {"vega-util", "vega/vega-util.js", "libjs-vega"},
    {"vega-loader", "vega/vega-loader.browser.js", "libjs-vega"},
    {"vega-format", "vega/vega-format.js", "libjs-vega"},
    {"vega-time", "vega/vega-time.js", "libjs-vega"},
    {"vega-dataflow", "vega/vega-dataflow.js", "libjs-vega"},
    {"vega-statistics", "vega/vega-statistics.js", "libjs-vega"},
    {"vega-scale", "vega/vega-scale.js", "libjs-vega"},
    {"vega-canvas", "vega/vega-canvas.browser.js", "libjs-vega"},
    {"vega-scenegraph", "vega/vega-scenegraph.js", "libjs-vega"},
    {"vega-expression", "vega/vega-expression.js", "libjs-vega"},
    {"vega-event-selector", "vega/vega-event-selector.js", "libjs-vega"},
    {"vega-selections", "vega/vega-selection.js", "libjs-vega"},
    {"vega-functions", "vega/vega-functions.js", "libjs-vega"},
    {"vega-encode", "vega/vega-encode.js", "libjs-vega"},
    {"vega-transforms", "vega/vega-transforms.js", "libjs-vega"},
    {"vega-view-transforms", "vega/vega-view-transforms.js", "libjs-vega"},
    {"vega-parser", "vega/vega-parser.js", "libjs-vega"},
    {"vega-runtime", "vega/vega-runtime.js", "libjs-vega"},
    {"vega-view", "vega/vega-view.js", "libjs-vega"},
};

/// A module file is ~200 KB at most; more is not a libjs-vega file.
constexpr std::size_t kMaxModuleBytes = 4u << 20;

constexpr std::string_view kShim = R"JS(
(function () {
  'use strict';
  var factories = {}, exported = {}, naming = null;
  function define(deps, factory) {
    if (naming === null) throw new Error('palp report: an anonymous define() outside the Vega modules');
    factories[naming] = {deps: deps, factory: factory};
    naming = null;
  }
  define.amd = {};
  function require(name) {
    if (Object.prototype.hasOwnProperty.call(exported, name)) return exported[name];
    var f = factories[name];
    if (!f) throw new Error('palp report: the Vega module ' + name + ' is not in this page');
    var exports = exported[name] = {};
    f.factory.apply(null, f.deps.map(function (d) { return d === 'exports' ? exports : require(d); }));
    return exports;
  }
  window.define = define;
  window.palpVegaModules = {
    next: function (name) { naming = name; },
    finish: function (names) {
      delete window.define;
      var vega = {};
      names.forEach(function (n) { if (n !== 'topojson-client') Object.assign(vega, require(n)); });
      Object.assign(require('vega-dataflow').transforms, require('vega-transforms'),
                    require('vega-view-transforms'), require('vega-encode'));
      window.vega = vega;
    }
  };
})();
)JS";

/// Text that may stand inside a <script> element: "</script" (in any case) would end it and
/// "<!--" may start an HTML comment state; "<\/script" and "<\!--" mean the same characters in a
/// JavaScript string or regular expression. (No other "</" is touched: "/</g" is a regular
/// expression.) Debian 12's modules contain neither.
std::string script_safe(std::string text) {
  for (std::size_t at = 0; at + 8 <= text.size(); ++at) {
    if (text[at] != '<') continue;
    if (text.compare(at, 4, "<!--") == 0) {
      text.insert(at + 1, "\\");
    } else if (text[at + 1] == '/') {
      std::string word = text.substr(at + 2, 6);
      for (char& ch : word) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      if (word == "script") text.insert(at + 1, "\\");
    }
  }
  return text;
}

}  // namespace

std::string vega_modules_js() {
  const char* env = std::getenv("PALP_JS_DIR");
  const fs::path dir = env != nullptr && *env != '\0' ? fs::path(env) : fs::path("/usr/share/javascript");
  std::string out = "<script>" + std::string(kShim) + "</script>\n";
  std::string names = "[";
  for (const ModuleFile& m : kModules) {
    const fs::path file = dir / m.file;
    const std::string text = format::read_bounded_or(file, kMaxModuleBytes, [&](const std::string& problem) {
      throw ConfigError(file.string() + ": " + problem + "; the report's page inlines this Vega module: install " +
                         "Debian's " + m.package + " (scripts/install-deps), or set PALP_JS_DIR to where " + m.file +
                         " is");
    });
    out += "<script>/* " + std::string(m.name) + ": " + m.file + " of Debian's " + m.package +
           " */\npalpVegaModules.next('" + m.name + "');\n" + script_safe(text) + "\n</script>\n";
    names += std::string(names.size() > 1 ? ", '" : "'") + m.name + "'";
  }
  out += "<script>palpVegaModules.finish(" + names + "]);</script>\n";
  return out;
}

}  // namespace palp::report::detail
