#pragma once
// How a state struct says what of it a checkpoint holds (run/checkpoint.cpp reads and writes the
// file). Each struct that changes during a run has a `serialize(ar, self)` next to its fields
// that names its sections and their columns, field by field:
//
//   ar.table("bodies", n, column(b.position), column(b.velocity), ...);  // n records, SoA
//   ar.table("plates", n, column(plates, &Plate::work), column(force_prev));  // members, arrays
//   ar.list("cracks", rows, &CrackRow::position, &CrackRow::area);  // a length the file sets
//   ar.record("solver", time, steps, dt);                             // one record of scalars
//
// A column's element is a Real, an integer, a bool, a Vec3 (3 words), a Quat (4), or a struct
// with an `archive_fields(record, value)` found by argument-dependent lookup that puts its fields
// in order; a table's width is the sum of its columns' word counts, from their types. The same
// function saves (`self` const) and restores (`self` mutable): the archive says which
// (`Archive::loading`).
#include <cstddef>

namespace rcdem {

// Element i of `v`, or its member `m`: one column of a table.
template <class Vec>
auto column(Vec& v) {
  return [&v](std::size_t i) -> decltype(auto) { return (v[i]); };
}
template <class Vec, class Member>
auto column(Vec& v, Member m) {
  return [&v, m](std::size_t i) -> decltype(auto) { return (v[i].*m); };
}

}  // namespace rcdem
