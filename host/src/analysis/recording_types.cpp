// SPDX-License-Identifier: Apache-2.0
// Recording in memory: its columns and append() (recording_types.hpp).
#include "palp/recording_types.hpp"

#include "palp/error.hpp"

namespace palp {

ColumnSet Recording::columns() const {
  ColumnSet c = ColumnSet::required().with(Column::rep);
  if (sample_index) c = c.with(Column::sample_index);
  if (i_cmd_A) c = c.with(Column::i_cmd_A);
  for (std::size_t k = 0; k < p_Pa.size(); ++k)
    if (p_Pa[k]) c = c.with(pressure_column(k));
  if (status) c = c.with(Column::status);
  return c;
}

void Recording::append(const RecordingRow& row) {
  t_s.push_back(row.t_s);
  i_A.push_back(row.i_A);
  z_mm.push_back(row.z_mm);
  rep.push_back(row.rep);
  if (sample_index) sample_index->push_back(row.sample_index);
  if (i_cmd_A) i_cmd_A->push_back(row.i_cmd_A);
  for (std::size_t k = 0; k < p_Pa.size(); ++k)
    if (p_Pa[k]) p_Pa[k]->push_back(row.p_Pa[k]);
  if (status) status->push_back(row.status);
}

}  // namespace palp
