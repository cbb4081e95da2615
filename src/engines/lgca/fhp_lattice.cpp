// The FHP lattice of one rank: initial state, halo exchange, the step, body force.
#include "narrows/engines/lgca/fhp_lattice.hpp"

#include "narrows/core/error.hpp"
#include "narrows/core/rng.hpp"
#include "narrows/engines/lgca/column_halo.hpp"
#include "narrows/engines/lgca/fhp_update.hpp"

#include <algorithm>
#include <cmath>

namespace narrows::lgca {

namespace {

constexpr double sqrt3_2 = 0.8660254037844386;

// Columns a slab needs: one halo column each side is enough for nearest neighbours, but a
// slab of one column would be its own halo source on both sides; two keep it simple.
constexpr int min_slab_columns = 2;

std::size_t round_up(std::size_t n, std::size_t m) { return (n + m - 1) / m * m; }

} // namespace

FhpLattice::FhpLattice(const FhpParams &params, MPI_Comm comm)
    : params_(params), table_(make_collision_table(params.model)),
      slabs_(comm, params.size_x, min_slab_columns) {
  if (params.size_y < 2 || params.size_y % 2 != 0)
    throw input_error("lattice size[1] = " + std::to_string(params.size_y) +
                      " must be even (rows alternate their half-spacing offset)");
  for (int s = 0; s < 128; ++s)
    bounce_[s] = bounce_back(static_cast<std::uint8_t>(s));
  nx_ = slabs_.local_columns();
  // Room for the halo columns and for 64-byte vector loads past the end of a row.
  stride_ = round_up(static_cast<std::size_t>(nx_) + 2 + 64, 64);
  const std::size_t bytes = stride_ * static_cast<std::size_t>(params.size_y);
  cur_.assign(bytes, 0);
  next_.assign(bytes, 0);

  const bool any_solid = params.walls || !params.obstacles.empty();
  std::int64_t solid_count = 0;
  if (any_solid) {
    solid_.assign(bytes, 0);
    for (int y = 0; y < params.size_y; ++y)
      for (int x = -1; x <= nx_; ++x) {
        const int gx = (first_column() + x + params.size_x) % params.size_x;
        bool s = params.walls && (y == 0 || y == params.size_y - 1);
        const double px = gx + 0.5 * (y % 2), py = y * sqrt3_2;
        for (const auto &ob : params.obstacles) {
          // Nearest periodic image in x and y.
          double dx = std::remainder(px - ob.x, static_cast<double>(params.size_x));
          double dy = std::remainder(py - ob.y, params.size_y * sqrt3_2);
          s = s || dx * dx + dy * dy <= ob.radius * ob.radius;
        }
        solid_[index(x, y)] = s ? 0xFF : 0;
        if (s && x >= 0 && x < nx_)
          ++solid_count;
      }
  }
  std::int64_t total = 0;
  MPI_Allreduce(&solid_count, &total, 1, MPI_INT64_T, MPI_SUM, comm);
  fluid_sites_ = static_cast<std::int64_t>(params.size_x) * params.size_y - total;
}

void FhpLattice::initialise(double density, double amplitude) {
  const int b = links(params_.model);
  const double rho = b * density;
  const double two_pi = 6.283185307179586;
  for (int y = 0; y < params_.size_y; ++y) {
    const double ux = amplitude * std::sin(two_pi * y / params_.size_y);
    std::array<double, 7> p{};
    for (int i = 0; i < 6; ++i)
      p[i] = std::clamp(density + rho / 3.0 * std::cos(M_PI * i / 3.0) * ux, 0.0, 1.0);
    p[6] = density;
    std::uint8_t *r = row(y);
    for (int x = 0; x < nx_; ++x) {
      if (solid(x, y)) {
        r[x] = 0;
        continue;
      }
      const std::uint64_t id =
          static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(params_.size_x) +
          static_cast<std::uint64_t>(first_column() + x);
      std::uint8_t s = 0;
      rng::Block u{};
      for (int i = 0; i < b; ++i) {
        if (i % 4 == 0)
          u = rng::draw(params_.seed, rng::Purpose::lgca_init, static_cast<std::uint64_t>(i / 4),
                        id);
        if (rng::open01(u[i % 4]) < p[i])
          s |= static_cast<std::uint8_t>(1u << i);
      }
      r[x] = s;
    }
  }
  time_ = 0;
}

void FhpLattice::exchange_halos() {
  // Row y starts at index(-1, y) = y * stride_: the halo columns are -1 and nx_.
  exchange_column_halos(slabs_, cur_.data(), stride_, params_.size_y, nx_, 40);
}

// Bit x of `bits` = chirality of local site x of row y at `step`: 128 bits per Philox block
// of global columns [128 k, 128 k + 128).
void FhpLattice::chirality_bits(int y, std::uint64_t step, std::vector<std::uint64_t> &bits) const {
  const int x0 = first_column();
  const std::uint64_t blocks = static_cast<std::uint64_t>(params_.size_x + 127) / 128;
  const int k0 = x0 / 128, k1 = (x0 + nx_ - 1) / 128;
  std::vector<std::uint64_t> raw(2 * static_cast<std::size_t>(k1 - k0 + 1) + 1, 0);
  for (int k = k0; k <= k1; ++k) {
    const auto b =
        rng::draw(params_.seed, rng::Purpose::lgca_chirality, step,
                  static_cast<std::uint64_t>(y) * blocks + static_cast<std::uint64_t>(k));
    raw[2 * (k - k0)] = b[0] | static_cast<std::uint64_t>(b[1]) << 32;
    raw[2 * (k - k0) + 1] = b[2] | static_cast<std::uint64_t>(b[3]) << 32;
  }
  const int off = x0 - 128 * k0; // bit of raw that is local site 0
  const std::size_t words = (static_cast<std::size_t>(nx_) + 63) / 64;
  bits.assign(words, 0);
  for (std::size_t w = 0; w < words; ++w) {
    const std::size_t at = static_cast<std::size_t>(off) + 64 * w;
    const std::size_t i = at / 64, s = at % 64;
    bits[w] = s == 0 ? raw[i] : (raw[i] >> s) | (raw[i + 1] << (64 - s));
  }
}

// Momentum injection: at a fluid site with link 3 occupied and link 0 empty, move the
// particle to link 0 with probability `force` (16-bit uniforms, 8 per Philox block of columns).
void FhpLattice::apply_force(int y, std::uint64_t step, std::uint8_t *out) const {
  const auto threshold = static_cast<std::uint32_t>(std::lround(params_.force * 65536.0));
  const std::uint64_t blocks = static_cast<std::uint64_t>(params_.size_x + 7) / 8;
  const int x0 = first_column();
  std::int64_t cached = -1;
  rng::Block u{};
  for (int x = 0; x < nx_; ++x) {
    const std::uint8_t s = out[x];
    if ((s & 0x09) != 0x08 || solid(x, y))
      continue;
    const int gx = x0 + x;
    if (gx / 8 != cached) {
      cached = gx / 8;
      u = rng::draw(params_.seed, rng::Purpose::lgca_force, step,
                    static_cast<std::uint64_t>(y) * blocks + static_cast<std::uint64_t>(cached));
    }
    const std::uint32_t r = (u[(gx % 8) / 2] >> (16 * (gx % 2))) & 0xFFFFu;
    if (r < threshold)
      out[x] = static_cast<std::uint8_t>((s & ~0x08u) | 0x01u);
  }
}

void FhpLattice::step() {
  exchange_halos();
  const std::uint64_t step = static_cast<std::uint64_t>(time_ + 1);
  const int Y = params_.size_y;
  std::vector<std::uint64_t> chir;
  RowUpdate r;
  static_assert(sizeof(table_.out) == 256, "the kernels index the table as [chirality][state]");
  r.table = table_.out[0].data();
  r.bounce = bounce_.data();
  r.n = nx_;
  for (int y = 0; y < Y; ++y) {
    chirality_bits(y, step, chir);
    r.below = cur_.data() + index(0, (y + Y - 1) % Y);
    r.here = cur_.data() + index(0, y);
    r.above = cur_.data() + index(0, (y + 1) % Y);
    r.out = next_.data() + index(0, y);
    r.solid = solid_.empty() ? nullptr : solid_.data() + index(0, y);
    r.chirality = chir.data();
    r.odd = y % 2;
    update_row(r);
    if (params_.force > 0.0)
      apply_force(y, step, r.out);
  }
  cur_.swap(next_);
  ++time_;
}

} // namespace narrows::lgca
