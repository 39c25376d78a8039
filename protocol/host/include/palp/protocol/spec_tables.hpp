// SPDX-License-Identifier: Apache-2.0
// The parts of SPEC.md that are the catalogue itself, generated so the document cannot drift:
// the message and enum tables, the stream byte-rate table, the canonical schema text and the
// worked examples' headers, CRCs and wire bytes.
// SPEC.md holds each between "<!-- BEGIN GENERATED name -->" and "<!-- END GENERATED name -->";
// a test fails when they differ from what this build generates.
#pragma once

#include <string>

namespace palp::proto {

std::string spec_message_tables();   ///< "messages"
std::string spec_enum_tables();      ///< "enums"
std::string spec_stream_rates();     ///< "stream-rates"
std::string canonical_schema_text(); ///< "schema"
/// "version": SPEC's first bullet, naming this build's protocol version and schema hash.
/// "verdict-example": the verdict text for a device one minor version older than this build.
std::string spec_verdict_example();
/// "example <label>": the golden example `label` (examples.hpp) field by field: header, one row
/// per field with its bytes and value, CRC and wire bytes. "" when there is no such example.
/// "example-frame <label>" (with_fields false): header, CRC and wire bytes only, for an example
/// whose payload SPEC.md explains by hand (a test checks those bytes against the payload).
std::string spec_example(const std::string& label, bool with_fields = true);

/// The generated block `name` (one of the above), or "" for an unknown name.
std::string spec_block(const std::string& name);

/// Replaces every generated block in a SPEC.md text with this build's; returns the new text.
/// Sets `error` (and returns "") when a block's markers are missing or unbalanced.
std::string refresh_spec(const std::string& spec, std::string& error);

}  // namespace palp::proto
