// A restarted fluid outside the colloids' cores: binned colloids, one pass over the fluid.
//
// Where the bound lies. A fluid particle sits inside r = sigma (the colloid's radius) now and
// then: it enters the WCA potential with its thermal kinetic energy, and over a long run the
// largest of those is about kT ln(particles x steps), some 60 kT for 1e25 particle-steps, which
// reaches phi(r) = 60 kT at r ~ 0.8 sigma; a coarse MD step or a strong flow takes it deeper.
// What no running simulation holds is a particle whose pair force has a component beyond the
// fixed-point range 2^22 (fixed::max_magnitude): the force loop refuses it with exit 3
// (colloids/pair_geometry.hpp, to_fixed) at the force evaluation that follows every MD move,
// so a checkpoint, written after a step, cannot contain one. With epsilon = kT and sigma = 2
// that is r < 0.40 sigma, a pair energy above 2.8e5 kT: far beyond anything thermal, so no
// state a run can reach is refused, and a continued run would stop at its first force
// evaluation on what is refused here (the same test, component by component).
#include "narrows/engines/mpcd/restart_checks.hpp"

#include "narrows/colloids/packing.hpp"
#include "narrows/colloids/potentials.hpp"
#include "narrows/core/error.hpp"
#include "narrows/core/fixed_point.hpp"
#include "narrows/engines/mpcd/invariants.hpp"
#include "narrows/run/collective.hpp"
#include "narrows/scene/parse.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <vector>

namespace narrows::mpcd {

namespace {

// Colloids binned on a grid of boxes at least one cut-off wide (periodic along x and z, and
// along y without walls): a point is tested against the colloids of its box and the adjacent
// ones only.
class ColloidBins {
public:
  // min_cut: bins at least this wide (a pair search of reach min_cut).
  ColloidBins(const colloids::Colloids &c, const mpcd::Box &box, double min_cut = 0.0)
      : c_(c), box_(box) {
    double cut = min_cut;
    for (const double r : c.radius)
      cut = std::max(cut, colloids::repulsive_cutoff(6, r));
    // At most about 4 bins per colloid (+ 64): memory O(Nc) in a large box with small colloids.
    const double most = 4.0 * static_cast<double>(c.size()) + 64.0;
    for (int k = 0; k < 3; ++k)
      n_[k] = k < box.dim && cut > 0.0
                  ? static_cast<int>(std::clamp(std::floor(box.length[k] / cut), 1.0, most))
                  : 1;
    while (static_cast<double>(n_[0]) * n_[1] * n_[2] > most) {
      int &widest = *std::max_element(n_.begin(), n_.begin() + box.dim);
      widest = std::max(1, widest / 2);
    }
    for (int k = 0; k < 3; ++k)
      inv_[k] = n_[k] / box.length[k];
    first_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
    std::vector<std::size_t> bin_of(c.size());
    for (std::size_t a = 0; a < c.size(); ++a) {
      std::array<double, 3> x{0.0, 0.0, 0.0};
      for (int k = 0; k < box.dim; ++k)
        x[k] = c.x[k][a];
      bin_of[a] = bin(coordinates(x));
      ++first_[bin_of[a] + 1];
    }
    for (std::size_t b = 1; b < first_.size(); ++b)
      first_[b] += first_[b - 1];
    members_.resize(c.size());
    std::vector<std::size_t> fill(first_.begin(), first_.end() - 1);
    for (std::size_t a = 0; a < c.size(); ++a)
      members_[fill[bin_of[a]]++] = a;
  }

  // f(colloid index) for every colloid in the bins around point x.
  template <class F> void around(const std::array<double, 3> &x, F &&f) const {
    const std::array<int, 3> home = coordinates(x);
    std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};
    for (int k = 0; k < box_.dim; ++k) {
      const bool periodic = !(box_.walls_y && k == 1);
      if (n_[k] < 3) { // every bin of the axis, each once
        lo[k] = -home[k];
        hi[k] = n_[k] - 1 - home[k];
      } else {
        lo[k] = periodic || home[k] > 0 ? -1 : 0;
        hi[k] = periodic || home[k] < n_[k] - 1 ? 1 : 0;
      }
    }
    std::array<int, 3> o{};
    for (o[2] = lo[2]; o[2] <= hi[2]; ++o[2])
      for (o[1] = lo[1]; o[1] <= hi[1]; ++o[1])
        for (o[0] = lo[0]; o[0] <= hi[0]; ++o[0]) {
          std::array<int, 3> b{};
          for (int k = 0; k < 3; ++k)
            b[k] = (home[k] + o[k] + n_[k]) % n_[k];
          const std::size_t at = bin(b);
          for (std::size_t i = first_[at]; i < first_[at + 1]; ++i)
            f(members_[i]);
        }
  }

private:
  std::array<int, 3> coordinates(const std::array<double, 3> &x) const {
    std::array<int, 3> b{0, 0, 0};
    for (int k = 0; k < box_.dim; ++k) {
      const double u = std::floor(x[k] * inv_[k]); // positions were checked finite and in the box
      b[k] = static_cast<int>(std::clamp(u, 0.0, static_cast<double>(n_[k] - 1)));
    }
    return b;
  }
  std::size_t bin(const std::array<int, 3> &b) const {
    return (static_cast<std::size_t>(b[2]) * n_[1] + b[1]) * n_[0] + b[0];
  }

  const colloids::Colloids &c_;
  const mpcd::Box &box_;
  std::array<int, 3> n_{1, 1, 1};
  std::array<double, 3> inv_{1.0, 1.0, 1.0};
  std::vector<std::size_t> first_, members_;
};

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

// Numbers of the checkpoint as io/checkpoint.cpp prints them: every digit.
std::string number_text(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

constexpr std::uint64_t no_row = ~std::uint64_t{0};

// One refusal on every rank: each rank offers its first bad row (no_row if none) and the line
// that describes it; every rank throws the line of the lowest bad row (so no rank waits for
// another that already gave up).
void refuse_first_bad_row(std::uint64_t bad_row, const std::string &line, MPI_Comm comm) {
  std::uint64_t first = no_row;
  MPI_Allreduce(&bad_row, &first, 1, MPI_UINT64_T, MPI_MIN, comm);
  if (first == no_row)
    return;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  int mine = bad_row == first ? rank : ranks, owner = 0;
  MPI_Allreduce(&mine, &owner, 1, MPI_INT, MPI_MIN, comm);
  std::uint64_t length = rank == owner ? line.size() : 0;
  MPI_Bcast(&length, 1, MPI_UINT64_T, owner, comm);
  std::string text = rank == owner ? line : std::string(length, ' ');
  MPI_Bcast(text.data(), static_cast<int>(length), MPI_CHAR, owner, comm);
  throw input_error(text);
}

// Every id of [0, total) exactly once over all ranks: each (id, row) goes to the rank that
// checks ids [ceil(d total / p), ceil((d + 1) total / p)), which keeps one row per id.
void check_unique_ids(const std::vector<std::uint64_t> &ids, std::uint64_t first_row,
                      std::uint64_t total, const std::string &dataset, const std::string &path,
                      MPI_Comm comm) {
  int p = 1, d = 0;
  MPI_Comm_size(comm, &p);
  MPI_Comm_rank(comm, &d);
  const auto owner = [&](std::uint64_t id) {
    return static_cast<int>(static_cast<unsigned __int128>(id) * p / total);
  };
  std::vector<int> send_counts(p, 0), recv_counts(p, 0), sdispl(p, 0), rdispl(p, 0);
  for (const auto id : ids)
    send_counts[owner(id)] += 2;
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < p; ++r) {
    sdispl[r] = sdispl[r - 1] + send_counts[r - 1];
    rdispl[r] = rdispl[r - 1] + recv_counts[r - 1];
  }
  std::vector<std::uint64_t> send(2 * ids.size()), recv(rdispl[p - 1] + recv_counts[p - 1]);
  std::vector<int> at = sdispl;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const int r = owner(ids[i]);
    send[at[r]++] = ids[i];
    send[at[r]++] = first_row + i;
  }
  MPI_Alltoallv(send.data(), send_counts.data(), sdispl.data(), MPI_UINT64_T, recv.data(),
                recv_counts.data(), rdispl.data(), MPI_UINT64_T, comm);
  const auto lo =
      static_cast<std::uint64_t>((static_cast<unsigned __int128>(total) * d + p - 1) / p);
  const auto hi =
      static_cast<std::uint64_t>((static_cast<unsigned __int128>(total) * (d + 1) + p - 1) / p);
  std::vector<std::uint64_t> row_of(hi - lo, no_row);
  std::uint64_t bad = no_row;
  std::string line;
  for (std::size_t k = 0; k < recv.size(); k += 2) {
    const std::uint64_t id = recv[k], row = recv[k + 1];
    std::uint64_t &seen = row_of[id - lo];
    if (seen == no_row) {
      seen = row;
      continue;
    }
    const std::uint64_t later = std::max(seen, row), earlier = std::min(seen, row);
    if (later < bad) {
      bad = later;
      line = path + ": " + dataset + " row " + std::to_string(later) + " holds id " +
             std::to_string(id) + ", as does row " + std::to_string(earlier) +
             "; allowed: every id from 0 to " + std::to_string(total - 1) + " once";
    }
  }
  refuse_first_bad_row(bad, line, comm);
}

} // namespace

void check_fluid_outside_colloids(const mpcd::Fluid &f, const colloids::Colloids &c,
                                  const mpcd::Box &box, double epsilon, double kT,
                                  const std::string &file, MPI_Comm comm) {
  const int D = box.dim;
  std::optional<std::string> line;
  std::uint64_t first = std::numeric_limits<std::uint64_t>::max();
  if (c.size() > 0) {
    const ColloidBins bins(c, box);
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (f.id[i] >= first)
        continue; // the smallest bad id is reported, whatever the rank count
      std::array<double, 3> x{0.0, 0.0, 0.0};
      for (int k = 0; k < D; ++k)
        x[k] = f.x[k][i];
      bins.around(x, [&](std::size_t a) {
        if (f.id[i] >= first)
          return;
        std::array<double, 3> d{0.0, 0.0, 0.0};
        double r2 = 0.0;
        for (int k = 0; k < D; ++k) {
          d[k] = x[k] - c.x[k][a];
          if (!(box.walls_y && k == 1))
            d[k] -= box.length[k] * std::nearbyint(d[k] / box.length[k]);
          r2 += d[k] * d[k];
        }
        const double sigma = c.radius[a];
        if (!(r2 < std::pow(colloids::repulsive_cutoff(6, sigma), 2)))
          return;
        const colloids::PairTerm t = colloids::repulsive_pair<6>(r2, sigma * sigma, epsilon);
        bool beyond = r2 == 0.0;
        for (int k = 0; k < D; ++k)
          beyond = beyond || !(std::abs(t.f_over_r * d[k]) < fixed::max_magnitude);
        if (!beyond)
          return;
        first = f.id[i];
        std::string at = "(";
        for (int k = 0; k < D; ++k)
          at += (k ? ", " : "") + number(x[k]);
        const double energy = r2 == 0.0 ? std::numeric_limits<double>::infinity() : t.energy;
        line = file + ": /particles/fluid/position/value: fluid particle id " +
               std::to_string(f.id[i]) + " at " + at + ") lies inside colloid id " +
               std::to_string(c.id[a]) + " at distance " + number(std::sqrt(r2)) +
               " from its centre (radius " + number(sigma) + "), pair energy " +
               number(energy / kT) +
               " kT; allowed: a state a run can reach (a WCA force component below " +
               number(fixed::max_magnitude) + ", beyond which a run stops)";
      });
    }
  }
  std::uint64_t smallest = first;
  MPI_Allreduce(&first, &smallest, 1, MPI_UINT64_T, MPI_MIN, comm);
  run::collectively(comm, [&] {
    if (line && first == smallest)
      throw input_error(*line);
  });
}

void check_stored_scene(const io::CheckpointInfo &info, const std::string &path) {
  // A stored scene that does not parse is refused by the restart's comparison of the scenes
  // (run::Shell), with its own line.
  scene::Scene stored;
  try {
    stored = scene::parse_scene(info.scene_text, path + ":/parameters/scene");
  } catch (const Error &) {
    return;
  }
  if (stored.run.seed != info.seed)
    throw input_error(path + ": /parameters/seed = " + std::to_string(info.seed) +
                      " but /parameters/scene has run.seed = " + std::to_string(stored.run.seed) +
                      "; allowed: the same seed");
  for (int k = 0; k < info.dimensions; ++k)
    if (stored.domain.size[k] != info.box[k])
      throw input_error(path + ": /particles/fluid/box/edges[" + std::to_string(k) +
                        "] = " + number_text(info.box[k]) +
                        " but /parameters/scene has domain.size[" + std::to_string(k) +
                        "] = " + number_text(stored.domain.size[k]) + "; allowed: the same box");
}

void check_restored_fluid(const mpcd::Fluid &f, const io::CheckpointInfo &info, std::uint64_t total,
                          const std::string &path, MPI_Comm comm) {
  // The state must be one the run can continue: finite, inside the box (between the walls),
  // every id once. The first bad row (lowest over all ranks) is refused on every rank.
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // The rows this rank read (io::read_species: a block of the rows by rank).
  const auto first_row =
      total * static_cast<std::uint64_t>(rank) / static_cast<std::uint64_t>(ranks);
  const std::string pos = "/particles/fluid/position/value",
                    vel = "/particles/fluid/velocity/value", ids = "/particles/fluid/id/value";
  std::uint64_t bad = no_row;
  std::string line;
  for (std::size_t i = 0; i < f.id.size() && bad == no_row; ++i) {
    const std::string row = " row " + std::to_string(first_row + i);
    if (f.id[i] >= total) {
      line = path + ": " + ids + row + " holds id " + std::to_string(f.id[i]) + "; allowed: 0 to " +
             std::to_string(total - 1);
    }
    for (int k = 0; k < f.dim && line.empty(); ++k) {
      const double x = f.x[k][i], v = f.v[k][i], L = info.box[k];
      if (!(x >= 0.0 && x <= L))
        line = path + ": " + pos + row + " component " + std::to_string(k) + " = " +
               number_text(x) + "; allowed: inside the box, 0 to " + number_text(L);
      else if (!std::isfinite(v))
        line = path + ": " + vel + row + " component " + std::to_string(k) + " = " +
               number_text(v) + "; allowed: a finite number";
    }
    if (!line.empty())
      bad = first_row + i;
  }
  refuse_first_bad_row(bad, line, comm);
  check_unique_ids(f.id, first_row, total, ids, path, comm);
}

void check_restored_colloids(const colloids::Colloids &c, const colloids::ContactHistory &contacts,
                             const scene::Scene &scene, const std::array<double, 3> &edges,
                             std::int64_t step, const std::string &path) {
  const int D = c.dim;
  const scene::Colloids &spec = *scene.colloids;
  mpcd::Box box;
  box.dim = D;
  box.walls_y = scene.walls.has_value();
  for (int k = 0; k < D; ++k)
    box.length[k] = scene.domain.size[k];
  const std::string set = path + ": /particles/colloids/";
  const auto colloid = [](std::size_t a) { return " (colloid id " + std::to_string(a) + ")"; };
  for (int k = 0; k < D; ++k)
    if (edges[k] != box.length[k])
      throw input_error(set + "box/edges[" + std::to_string(k) + "] = " + number_text(edges[k]) +
                        "; allowed: " + number_text(box.length[k]) + ", the scene's domain.size[" +
                        std::to_string(k) + "]");
  const bool hard = spec.contacts == scene::ColloidContacts::hard;
  const bool springs = spec.contacts == scene::ColloidContacts::spring;
  const bool md = spec.coupling == scene::ColloidCoupling::md;
  // The hard-sphere event loop's rounding margin (colloids/hard_spheres.cpp).
  const double margin = 1e-6 * (1.0 + box.length[0]);
  // Hard contacts never create an overlap, but keep those a packed start leaves: up to the
  // packing's acceptance tolerance of the smallest radius (colloids/packing.hpp).
  double r_min = std::numeric_limits<double>::infinity();
  for (const double r : c.radius)
    r_min = std::min(r_min, r);
  const double hard_allowance = colloids::PackingParams{}.tolerance * r_min + margin;
  const double Ly = box.length[1];
  // Rows are in id order (read_colloids): row a is colloid id a.
  for (std::size_t a = 0; a < c.size(); ++a) {
    const double r = c.radius[a];
    for (int k = 0; k < D; ++k) {
      if (!(c.x[k][a] >= 0.0 && c.x[k][a] <= box.length[k]))
        throw input_error(set + "position/value" + colloid(a) + " component " + std::to_string(k) +
                          " = " + number_text(c.x[k][a]) +
                          "; allowed: inside the scene's box, 0 to " + number_text(box.length[k]));
      if (!(std::abs(c.v[k][a]) <= max_speed))
        throw input_error(set + "velocity/value" + colloid(a) + " component " + std::to_string(k) +
                          " = " + number_text(c.v[k][a]) + "; allowed: |v| <= " +
                          number_text(max_speed) + ", the run's speed limit");
    }
    for (int k = D == 2 ? 2 : 0; k < 3; ++k)
      if (!(std::abs(c.omega[k][a]) * r <= max_speed))
        throw input_error(set + "angular_velocity_" + std::string(1, "xyz"[k]) + "/value" +
                          colloid(a) + " = " + number_text(c.omega[k][a]) +
                          "; allowed: |omega| r <= " + number_text(max_speed) +
                          ", the run's speed limit at the surface");
    if (!box.walls_y)
      continue;
    const double y = c.x[1][a];
    const std::string where = set + "position/value" + colloid(a) +
                              " component 1 = " + number_text(y) + " (radius " + number_text(r) +
                              ")";
    if (!(y > 0.0 && y < Ly))
      throw input_error(where + "; allowed: a centre between the walls, 0 < y < " +
                        number_text(Ly));
    if (hard && !(y >= r - hard_allowance && y <= Ly - r + hard_allowance))
      throw input_error(where +
                        " overlaps a wall; allowed: hard contacts keep r <= y <= L_y - r "
                        "(within " +
                        number_text(hard_allowance) + ", the deepest overlap a packing leaves)");
    if (md) {
      const double sw = spec.wall_sigma_of(r);
      double force = 0.0;
      for (const double h : {y, Ly - y})
        if (h < colloids::wall_cutoff(sw))
          force = std::max(force,
                           std::abs(colloids::wall_term(h, sw, spec.epsilon, spec.wall_q).force));
      if (!(force < fixed::max_magnitude))
        throw input_error(where + " is so deep in the wall potential that its force is " +
                          number_text(force) + "; allowed: a wall force below " +
                          number_text(fixed::max_magnitude) + ", beyond which a run stops");
    }
  }
  // Pairs closer than r_a + r_b (the reach of every contact model and of the 48-24 cut-off
  // 2^(1/24) (r_a + r_b) of MD colloids), found through bins at least 2 r_max (+ that cut-off)
  // wide.
  double r_max = 0.0;
  for (const double r : c.radius)
    r_max = std::max(r_max, r);
  const double reach = std::pow(2.0, 1.0 / 24.0) * 2.0 * r_max;
  std::set<std::pair<std::uint64_t, std::uint64_t>> touching; // (spring contacts)
  if (c.size() > 1) {
    const ColloidBins bins(c, box, reach);
    for (std::size_t a = 0; a < c.size(); ++a) {
      std::array<double, 3> x{0.0, 0.0, 0.0};
      for (int k = 0; k < D; ++k)
        x[k] = c.x[k][a];
      bins.around(x, [&](std::size_t b) {
        if (b <= a)
          return;
        std::array<double, 3> d{0.0, 0.0, 0.0};
        double r2 = 0.0;
        for (int k = 0; k < D; ++k) {
          d[k] = x[k] - c.x[k][b];
          if (!(box.walls_y && k == 1))
            d[k] -= box.length[k] * std::nearbyint(d[k] / box.length[k]);
          r2 += d[k] * d[k];
        }
        const double R = c.radius[a] + c.radius[b], dist = std::sqrt(r2);
        std::string refused;
        if (hard && dist < R - hard_allowance)
          refused = "hard contacts allow none (within " + number_text(hard_allowance) +
                    ", the deepest overlap a packing leaves)";
        else if (springs && !(dist > std::max(c.radius[a], c.radius[b])))
          refused = "spring contacts allow overlaps with each centre outside the other colloid";
        else if (md && dist < std::pow(2.0, 1.0 / 24.0) * R) {
          const colloids::PairTerm t = colloids::repulsive_pair<24>(r2, R * R, spec.epsilon);
          bool beyond = r2 == 0.0;
          for (int k = 0; k < D; ++k)
            beyond = beyond || !(std::abs(t.f_over_r * d[k]) < fixed::max_magnitude);
          if (beyond)
            refused = "MD colloids allow a 48-24 pair force below " +
                      number_text(fixed::max_magnitude) + ", beyond which a run stops";
        }
        if (!refused.empty())
          throw input_error(set + "position/value: colloid ids " + std::to_string(a) + " and " +
                            std::to_string(b) + " overlap: centres " + number_text(dist) +
                            " apart, radii " + number_text(c.radius[a]) + " and " +
                            number_text(c.radius[b]) + "; allowed: " + refused);
        if (springs && dist < R - margin)
          touching.insert({a, b});
      });
    }
  }
  if (!springs)
    return;
  if (box.walls_y)
    for (std::size_t a = 0; a < c.size(); ++a) {
      if (c.x[1][a] < c.radius[a] - margin)
        touching.insert({a, colloids::wall_low_id});
      if (Ly - c.x[1][a] < c.radius[a] - margin)
        touching.insert({a, colloids::wall_high_id});
    }
  // Each contact row between bodies that touch (at the last force evaluation, which follows the
  // last move: the history is that of the stored positions, within the rounding margin).
  const std::string cset = path + ": /particles/contacts/";
  for (std::size_t j = 0; j < contacts.size(); ++j) {
    const std::uint64_t a = contacts.owner[j], p = contacts.partner[j];
    double gap = 0.0; // > 0: apart
    std::string what;
    if (colloids::is_wall_id(p)) {
      const double h = p == colloids::wall_low_id ? c.x[1][a] : Ly - c.x[1][a];
      gap = h - c.radius[a];
      what = "colloid id " + std::to_string(a) + " and the wall " +
             (p == colloids::wall_low_id ? "y = 0" : "y = L_y") + ": its centre " + number_text(h) +
             " from the wall, radius " + number_text(c.radius[a]);
    } else {
      double r2 = 0.0;
      for (int k = 0; k < D; ++k) {
        double d = c.x[k][a] - c.x[k][p];
        if (!(box.walls_y && k == 1))
          d -= box.length[k] * std::nearbyint(d / box.length[k]);
        r2 += d * d;
      }
      gap = std::sqrt(r2) - c.radius[a] - c.radius[p];
      what = "colloid ids " + std::to_string(a) + " and " + std::to_string(p) + ": centres " +
             number_text(std::sqrt(r2)) + " apart, radii " + number_text(c.radius[a]) + " and " +
             number_text(c.radius[p]);
    }
    if (gap > margin)
      throw input_error(cset + "owner_id/value, partner_id/value row " + std::to_string(j) +
                        " holds a contact of " + what +
                        ", which do not touch; allowed: contacts between touching bodies only");
    // The tangential spring as the force loop leaves it (colloids/springs.cpp): capped at
    // |k_t xi| <= mu k_n delta after every update (Coulomb), zero without k_t, and a force the
    // fixed-point sums can hold.
    const scene::ColloidSprings &k = spec.spring;
    const double mu = colloids::is_wall_id(p) ? k.mu_cw : k.mu_cc;
    const double xi =
        std::hypot(contacts.xi[0][j], contacts.xi[1][j], D == 3 ? contacts.xi[2][j] : 0.0);
    const double delta = std::max(-gap, 0.0);
    double most = fixed::max_magnitude / (k.kt * std::max(1.0, c.radius[a]));
    std::string rule = "a force and torque the fixed-point sums hold";
    if (k.kt == 0.0) {
      most = 0.0;
      rule = "colloids.spring.kt = 0";
    } else if (std::isfinite(mu) && mu * k.kn * delta / k.kt * (1.0 + 1e-9) + 1e-12 < most) {
      most = mu * k.kn * delta / k.kt * (1.0 + 1e-9) + 1e-12;
      rule = "mu k_n delta / k_t, the Coulomb cap";
    }
    rule = number_text(most) + " (" + rule + ")";
    if (!(xi <= most))
      throw input_error(cset + "tangential_displacement/value row " + std::to_string(j) +
                        " (contact of " + what + ") has length " + number_text(xi) +
                        "; allowed: at most " + rule);
    touching.erase({a, p});
  }
  if (!touching.empty() && step > 0) {
    const auto [a, p] = *touching.begin();
    throw input_error(
        cset + "owner_id/value: no contact row of colloid id " + std::to_string(a) + " and " +
        (colloids::is_wall_id(p)
             ? std::string(p == colloids::wall_low_id ? "the wall y = 0" : "the wall y = L_y")
             : "colloid id " + std::to_string(p)) +
        ", which overlap (rows removed, or the contact group deleted); allowed: a "
        "contact row for every touching pair");
  }
}

} // namespace narrows::mpcd
