// SPDX-License-Identifier: Apache-2.0
// An identification result directory (sweep, free air) as one HDF5 file (docs/hdf5-format.md
// "An identification file"): the result's group and the measured response as typed columns.
#include <string>
#include <vector>

#include "hdf5/h5.hpp"
#include "hdf5/h5_result.hpp"
#include "palp/analysis/frf_table.hpp"
#include "palp/error.hpp"
#include "palp/hdf5.hpp"
#include "palp/identification_result.hpp"

namespace palp {

namespace fs = std::filesystem;

namespace {

using namespace hdf5_detail;

constexpr std::string_view kIdentificationExperiment = "identification";
constexpr const char* kFrfFile = "frf.csv";

void write_frf_group(hid_t parent, const Where& w, const analysis::Frf& frf) {
  const Id g = create_group(parent, w);
  std::vector<double> f, re, im, sigma;
  for (const analysis::FrfLine& l : frf.lines) {
    f.push_back(l.f_Hz);
    re.push_back(l.G_m_per_N.real());
    im.push_back(l.G_m_per_N.imag());
    sigma.push_back(l.sigma_m_per_N);
  }
  put_column<double>(g.get(), "f_Hz", f, "Hz", w);
  put_column<double>(g.get(), "re_m_per_N", re, "m/N", w);
  put_column<double>(g.get(), "im_m_per_N", im, "m/N", w);
  put_column<double>(g.get(), "sigma_m_per_N", sigma, "m/N", w);
  put_attr(g.get(), "lines", static_cast<std::uint64_t>(frf.lines.size()), w);
}

/// The response back, checked by the one reader of response tables (frf_table.hpp): the columns
/// as the table frf.csv held, parsed again, so the file gives what read_frf_table gave.
analysis::Frf read_frf_group(hid_t parent, const Where& w_parent, const fs::path& file) {
  const Id g = open_group(parent, "frf", w_parent);
  const Where w = w_parent.at("frf");
  const std::uint64_t limit = max_rows(file, sizeof(double));
  const std::vector<double> f = get_column<double>(g.get(), "f_Hz", limit, w);
  const std::vector<double> re = get_column<double>(g.get(), "re_m_per_N", limit, w);
  const std::vector<double> im = get_column<double>(g.get(), "im_m_per_N", limit, w);
  const std::vector<double> sigma = get_column<double>(g.get(), "sigma_m_per_N", limit, w);
  if (re.size() != f.size() || im.size() != f.size() || sigma.size() != f.size())
    fail(w, "columns of unequal length (f_Hz " + std::to_string(f.size()) + ", re_m_per_N " +
                std::to_string(re.size()) + ", im_m_per_N " + std::to_string(im.size()) + ", sigma_m_per_N " +
                std::to_string(sigma.size()) + ")");
  analysis::Frf table;
  for (std::size_t k = 0; k < f.size(); ++k) {
    analysis::FrfLine& l = table.lines.emplace_back();
    l.f_Hz = f[k];
    l.G_m_per_N = {re[k], im[k]};
    l.sigma_m_per_N = sigma[k];
  }
  try {
    return analysis::parse_frf_table(format_frf_table(table), w.object + " (as a table)");
  } catch (const RecordingError& e) {
    fail(w, e.what());
  }
}

}  // namespace

LoadedIdentification identification_of(LoadedResult result) {
  if (result.experiment != kIdentificationExperiment)
    throw ConfigError(result.dir.string() + ": an " + result.experiment + " result, not an identification");
  LoadedIdentification out;
  std::error_code ec;
  if (fs::exists(result.dir / kFrfFile, ec)) out.frf = analysis::read_frf_table(result.dir / kFrfFile);
  out.result = std::move(result);
  return out;
}

void write_identification_hdf5(const fs::path& path, const LoadedIdentification& id, Overwrite overwrite) {
  if (id.result.experiment != kIdentificationExperiment)
    throw ConfigError(path.string() + ": an " + id.result.experiment + " result is not an identification");
  write_palp_file(path, overwrite, kHdf5ContentIdentification, [&](hid_t root) {
    const Where w{path.string(), "/result"};
    write_result_group(root, w, id.result);
    if (id.frf) {
      const Id g = open_group(root, "result", Where{path.string(), "/"});
      write_frf_group(g.get(), w.at("frf"), *id.frf);
    }
  });
}

LoadedIdentification read_identification_hdf5(const fs::path& path) {
  const Id f = open_palp_file(path, kHdf5ContentIdentification);
  const Where root{path.string(), "/"};
  LoadedIdentification out;
  out.result = read_result_group(f.get(), "result", root, path);
  if (out.result.experiment != kIdentificationExperiment)
    fail(root.at("result").at("result_json"), "its experiment is \"" + out.result.experiment + "\", not \"identification\"");
  const Id g = open_group(f.get(), "result", root);
  if (has_link(g.get(), "frf")) out.frf = read_frf_group(g.get(), root.at("result"), path);
  return out;
}

}  // namespace palp
