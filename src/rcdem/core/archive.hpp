#pragma once
// How a state struct says what of it a checkpoint holds (run/checkpoint.cpp reads and writes the
// file). Each struct that changes during a run has a `serialize(ar, self)` next to its fields
// that names its sections and their columns, field by field:
//
//   ar.table("bodies", n, column("position", "m", b.position), ...);  // n records, SoA
//   ar.table("plates", n, column("work", "J", plates, &Plate::work));  // a member of each
//   ar.list("cracks", rows, member("area", "m^2", &CrackRow::area));   // a length the file sets
//   ar.record("solver", named("time", "s", time), ...);               // one record of scalars
//
// A column's element is a Real, an integer, a bool, a Vec3 (3 words), a Quat (4), or a struct
// with an `archive_fields(record, value)` found by argument-dependent lookup that puts its fields
// in order, each named (`r.put(named("fn", "N", s.fn))`); a table's width is the sum of its
// columns' word counts, from their types. The same
// function saves (`self` const) and restores (`self` mutable): the archive says which
// (`Archive::loading`).
#include <cstddef>

namespace rcdem {

// Every column, record field and struct field is named with its unit (SI: "m", "N", "J",
// "N*m", ...; "1" for a dimensionless number, "-" for a count, an index or a flag): the binary
// checkpoint ignores the names, a self-describing one (HDF5) and docs/checkpoint.md's layout use
// them.
template <class T>
struct Named {
  const char* name;
  const char* unit;
  T& value;
};
template <class T>
Named<T> named(const char* name, const char* unit, T& value) {
  return {name, unit, value};
}

// One column of a table: element i of a vector, of its member, or what a callable returns.
template <class F>
struct Column {
  const char* name;
  const char* unit;
  F at;
  decltype(auto) operator()(std::size_t i) const { return at(i); }
};
template <class Vec>
auto column(const char* name, const char* unit, Vec& v) {
  auto at = [&v](std::size_t i) -> decltype(auto) { return (v[i]); };
  return Column<decltype(at)>{name, unit, at};
}
template <class Vec, class Member>
auto column(const char* name, const char* unit, Vec& v, Member m) {
  auto at = [&v, m](std::size_t i) -> decltype(auto) { return (v[i].*m); };
  return Column<decltype(at)>{name, unit, at};
}
template <class F>
auto column_of(const char* name, const char* unit, F at) {
  return Column<F>{name, unit, at};
}

// A member of a list's elements.
template <class M>
struct NamedMember {
  const char* name;
  const char* unit;
  M m;
};
template <class M>
NamedMember<M> member(const char* name, const char* unit, M m) {
  return {name, unit, m};
}

}  // namespace rcdem
