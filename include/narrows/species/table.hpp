// A particle species as one table of named, typed per-row fields (issue 30 item 3). Each species
// (the fluid: mpcd::table, colloids: colloids::table, their contact history) declares its fields
// once, one line each, with flags that say where a field goes: migration to another rank, ghost
// copies, checkpoints, trajectory frames. Everything that handles whole rows is derived from that
// one list: resizing, copying and reordering rows, gathering all rows on every rank (here), the
// arrays the Exchange sends (parallel::view), the datasets of a checkpoint
// (io::checkpoint_fields) and the series of a trajectory. So a field added to a species (one line
// in its table, or at run time through species::Extra) migrates, is copied to ghosts, is stored
// and restored without further edits.
//
// A table is a view: it points at the arrays of one instance of the species (a few fields, built
// when needed; never per particle). Kernels keep using the species' arrays directly.
#pragma once

#include <mpi.h>

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

namespace narrows::species {

// What a field takes part in besides being a column of its species.
enum Flag : unsigned {
  // Sent with its row to the rank that takes the row over (Exchange::migrate). A field without it
  // stays row-aligned on each rank, and a row that arrives gets the field's fill.
  migrates = 1u << 0,
  // Carried by ghost copies (Exchange::copy); a ghost row of a field without it gets the fill.
  ghost = 1u << 1,
  // Stored in checkpoints as /particles/<species>/<name>/value (see Shape).
  checkpoint = 1u << 2,
  // A series /particles/<species>/<name>/{value, step, time} in trajectory frames.
  trajectory = 1u << 3,
  // Checkpoints written before the field existed lack it: a restart from one leaves the fill (or
  // what the reader of that species derives instead, e.g. colloid radii from the scene).
  added_later = 1u << 4,
};
inline constexpr unsigned everywhere = migrates | ghost | checkpoint | trajectory;

// One component array of a field, and the value a new row gets.
using Array =
    std::variant<std::vector<double> *, std::vector<std::uint64_t> *, std::vector<std::uint32_t> *>;

// A value of a column as one 8-byte word of a message (doubles by their bits: exact) and back.
template <class T> std::uint64_t to_word(T v) {
  if constexpr (std::is_same_v<T, double>)
    return std::bit_cast<std::uint64_t>(v);
  else
    return v;
}
template <class T> T from_word(std::uint64_t w) {
  if constexpr (std::is_same_v<T, double>)
    return std::bit_cast<double>(w);
  else
    return static_cast<T>(w);
}

struct Column {
  Array array{static_cast<std::vector<double> *>(nullptr)};
  double fill = 0.0;

  std::size_t size() const;
  void resize(std::size_t n) const;                      // new rows get the fill
  void move_row(std::size_t to, std::size_t from) const; // within the array
};

// How a checkpoint stores a field.
enum class Shape {
  scalar, // one column: dataset [N] (float64, or uint64 for words)
  vector, // `dim` columns: one dataset [N][d] float64
  split,  // one dataset [N] per column, named <name>_<suffix>, from column first_stored on
};

struct Field {
  std::string_view name;
  Shape shape = Shape::scalar;
  unsigned flags = 0;
  std::array<Column, 4> column{};
  int count = 0;             // columns in use
  std::string_view suffixes; // split: one letter per column ("xyz", "wxyz")
  int first_stored = 0;      // split: columns before it are not stored (a 2D spin: only z)

  bool has(unsigned flag) const { return (flags & flag) == flag; }
  std::span<const Column> columns() const {
    return {column.data(), static_cast<std::size_t>(count)};
  }
  // The checkpoint dataset of column k: <name>_<suffix k> for split fields, else <name>.
  std::string stored_name(int k) const;
};

class Extra;

// The fields of one instance of a species, in declaration order (checkpoints store its vector
// fields, then word fields, then the others, each kind in this order).
class Table {
public:
  Table(std::string_view species, int dim) : species_(species), dim_(dim) {}

  // ---- declarations, one line per field ----
  // `dim` double arrays of a (k < dim), stored as [N][d].
  Table &vector(std::string_view name, std::array<std::vector<double>, 3> &a, unsigned flags);
  // One array (double, uint64 or uint32), stored as [N].
  template <class T>
  Table &scalar(std::string_view name, std::vector<T> &a, unsigned flags, double fill = 0.0) {
    Field f;
    f.name = name;
    f.flags = flags;
    f.column[0] = {&a, fill};
    f.count = 1;
    return add(f);
  }
  // N double arrays (all of them exist in any dimension), stored one dataset per column
  // <name>_<suffixes[k]> from column first_stored on; fill[k] for new rows.
  template <std::size_t N>
  Table &split(std::string_view name, std::array<std::vector<double>, N> &a,
               std::string_view suffixes, int first_stored, unsigned flags,
               const std::array<double, N> &fill = {}) {
    static_assert(N <= 4);
    Field f;
    f.name = name;
    f.shape = Shape::split;
    f.flags = flags;
    for (std::size_t k = 0; k < N; ++k)
      f.column[k] = {&a[k], fill[k]};
    f.count = static_cast<int>(N);
    f.suffixes = suffixes;
    f.first_stored = first_stored;
    return add(f);
  }
  // The fields an instance carries beyond the declared ones (after them, in the order added).
  Table &extra(Extra &e);

  std::string_view species() const { return species_; }
  int dim() const { return dim_; }
  const std::vector<Field> &fields() const { return fields_; }
  const Field *find(std::string_view name) const;

  // ---- whole rows, derived from the fields ----
  std::size_t size() const; // rows (of the first column)
  // Every column to n rows; new rows get their fill.
  void resize(std::size_t n) const;
  // Row `row` of `from` (a table of the same species with the same fields) into row `to`.
  void copy_row(std::size_t to, const Table &from, std::size_t row) const;
  // Reorders the rows: row j becomes the old row order[j] (a permutation of all rows).
  void permute(const std::vector<std::size_t> &order) const;
  // Keeps the rows with keep[i], in order.
  void keep_rows(const std::vector<bool> &keep) const;

  // A table of a const instance (gathering, writing): reading only, which the mutators enforce.
  Table &read_only() {
    read_only_ = true;
    return *this;
  }

private:
  Table &add(const Field &f);
  void check_writable() const;

  std::string_view species_;
  int dim_ = 2;
  std::vector<Field> fields_;
  bool read_only_ = false;
};

// Per-row fields added to an instance at run time (a quantity an analysis computes, a test's
// scratch field): named, typed (double or uint64) and flagged like declared fields, and held by
// the instance, so copies of it carry them. A species whose table ends with .extra(its Extra)
// treats them as its own: they resize, migrate, go to ghosts, are gathered, checkpointed and
// restored like any other field.
class Extra {
public:
  // Adds a field (rows: the species' current number of rows, each `fill`); returns its array.
  // The name must be new to the species (Table::extra refuses a duplicate).
  template <class T>
  std::vector<T> &add(std::string name, unsigned flags, std::size_t rows, double fill = 0.0) {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::uint64_t>);
    fields_.push_back({std::move(name), flags, fill, std::vector<T>(rows, static_cast<T>(fill))});
    return std::get<std::vector<T>>(fields_.back().values);
  }
  template <class T> std::vector<T> &get(std::string_view name) {
    return std::get<std::vector<T>>(find(name).values);
  }
  template <class T> const std::vector<T> &get(std::string_view name) const {
    return std::get<std::vector<T>>(const_cast<Extra *>(this)->find(name).values);
  }
  bool empty() const { return fields_.empty(); }
  // The same fields without rows (for another instance of the species to be filled).
  Extra same_fields() const {
    Extra e = *this;
    for (auto &f : e.fields_)
      std::visit([](auto &values) { values.clear(); }, f.values);
    return e;
  }

private:
  friend class Table;
  struct Entry {
    std::string name;
    unsigned flags = 0;
    double fill = 0.0;
    std::variant<std::vector<double>, std::vector<std::uint64_t>> values;
  };
  Entry &find(std::string_view name);
  std::deque<Entry> fields_; // (a deque: arrays handed out stay where they are)
};

// All rows of `mine` of every rank, in rank order, into `all` (a table of another instance of the
// same species with the same fields; resized), on every rank (collective).
void gather(const Table &mine, Table &all, MPI_Comm comm);

} // namespace narrows::species
