// The species table: declarations, and the row operations every species gets from it.
#include "narrows/species/table.hpp"

#include "narrows/core/error.hpp"

#include <string>

namespace narrows::species {

std::size_t Column::size() const {
  return std::visit([](auto *a) { return a->size(); }, array);
}

void Column::resize(std::size_t n) const {
  std::visit(
      [n, this](auto *a) {
        using T = typename std::remove_pointer_t<decltype(a)>::value_type;
        a->resize(n, static_cast<T>(fill));
      },
      array);
}

void Column::move_row(std::size_t to, std::size_t from) const {
  std::visit([=](auto *a) { (*a)[to] = (*a)[from]; }, array);
}

std::string Field::stored_name(int k) const {
  std::string s(name);
  if (shape == Shape::split)
    (s += '_') += suffixes.at(static_cast<std::size_t>(k));
  return s;
}

Table &Table::vector(std::string_view name, std::array<std::vector<double>, 3> &a, unsigned flags) {
  Field f;
  f.name = name;
  f.shape = Shape::vector;
  f.flags = flags;
  for (int k = 0; k < dim_; ++k)
    f.column[k] = {&a[k], 0.0};
  f.count = dim_;
  return add(f);
}

Table &Table::add(const Field &f) {
  if (find(f.name) != nullptr)
    throw Error(ExitCode::other, "species " + std::string(species_) + ": a second field named " +
                                     std::string(f.name));
  fields_.push_back(f);
  return *this;
}

Table &Table::extra(Extra &e) {
  for (auto &entry : e.fields_) {
    Field f;
    f.name = entry.name;
    f.flags = entry.flags;
    std::visit([&](auto &values) { f.column[0] = {&values, entry.fill}; }, entry.values);
    f.count = 1;
    add(f);
  }
  return *this;
}

const Field *Table::find(std::string_view name) const {
  for (const Field &f : fields_)
    if (f.name == name)
      return &f;
  return nullptr;
}

std::size_t Table::size() const { return fields_.empty() ? 0 : fields_[0].column[0].size(); }

void Table::check_writable() const {
  if (read_only_)
    throw Error(ExitCode::other,
                "species " + std::string(species_) + ": rows changed through a read-only table");
}

void Table::resize(std::size_t n) const {
  check_writable();
  for (const Field &f : fields_)
    for (const Column &c : f.columns())
      c.resize(n);
}

void Table::copy_row(std::size_t to, const Table &from, std::size_t row) const {
  check_writable();
  if (from.fields_.size() != fields_.size())
    throw Error(ExitCode::other, "species " + std::string(species_) +
                                     ": rows copied between tables of other fields");
  for (std::size_t f = 0; f < fields_.size(); ++f)
    for (int k = 0; k < fields_[f].count; ++k)
      std::visit(
          [&](auto *dst) {
            using V = std::remove_pointer_t<decltype(dst)>;
            (*dst)[to] = (*std::get<V *>(from.fields_[f].column[k].array))[row];
          },
          fields_[f].column[k].array);
}

void Table::permute(const std::vector<std::size_t> &order) const {
  check_writable();
  for (const Field &f : fields_)
    for (const Column &c : f.columns())
      std::visit(
          [&](auto *a) {
            const auto old = *a;
            for (std::size_t j = 0; j < order.size(); ++j)
              (*a)[j] = old[order[j]];
          },
          c.array);
}

void Table::keep_rows(const std::vector<bool> &keep) const {
  check_writable();
  for (const Field &f : fields_)
    for (const Column &c : f.columns())
      std::visit(
          [&](auto *a) {
            std::size_t n = 0;
            for (std::size_t i = 0; i < keep.size(); ++i)
              if (keep[i])
                (*a)[n++] = (*a)[i];
            a->resize(n);
          },
          c.array);
}

Extra::Entry &Extra::find(std::string_view name) {
  for (auto &e : fields_)
    if (e.name == name)
      return e;
  throw Error(ExitCode::other, "no extra field named " + std::string(name));
}

void gather(const Table &mine, Table &all, MPI_Comm comm) {
  // Rows of one 8-byte word per column (doubles by their bits: exact).
  std::size_t W = 0;
  for (const Field &f : mine.fields())
    W += static_cast<std::size_t>(f.count);
  const std::size_t n = mine.size();
  std::vector<std::uint64_t> rows(n * W);
  std::size_t w = 0;
  for (const Field &f : mine.fields())
    for (const Column &c : f.columns()) {
      std::visit(
          [&](auto *a) {
            for (std::size_t i = 0; i < n; ++i)
              rows[i * W + w] = to_word((*a)[i]);
          },
          c.array);
      ++w;
    }
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int count = static_cast<int>(n * W);
  std::vector<int> counts(ranks), displs(ranks, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < ranks; ++r)
    displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<std::uint64_t> words(static_cast<std::size_t>(displs[ranks - 1] + counts[ranks - 1]));
  MPI_Allgatherv(rows.data(), count, MPI_UINT64_T, words.data(), counts.data(), displs.data(),
                 MPI_UINT64_T, comm);
  if (all.fields().size() != mine.fields().size())
    throw Error(ExitCode::other, "species " + std::string(mine.species()) +
                                     ": gathered into a table of other fields");
  const std::size_t total = W ? words.size() / W : 0;
  all.resize(total);
  w = 0;
  for (const Field &f : all.fields())
    for (const Column &c : f.columns()) {
      std::visit(
          [&](auto *a) {
            using T = typename std::remove_pointer_t<decltype(a)>::value_type;
            for (std::size_t i = 0; i < total; ++i)
              (*a)[i] = from_word<T>(words[i * W + w]);
          },
          c.array);
      ++w;
    }
}

} // namespace narrows::species
