#include "plumage/checksum.hpp"
#include "plumage/reflection_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/config_document.hpp"
#include "plumage/error.hpp"
#include "plumage/input_file.hpp"

namespace plumage {

namespace {

constexpr char kMagic[8] = {'P', 'L', 'M', 'R', 'T', 'A', 'B', '\0'};
constexpr std::uint32_t kVersion = 1;
constexpr std::uint32_t kByteOrder = 0x01020304u;
constexpr const char* kUnits = "lambda:nm; axes:cos_theta,cos_phi_local; entry:jones(s,p) ss,sp,ps,pp re/im float64";

std::uint64_t fnv1a(const char* data, std::size_t n, std::uint64_t h = kFnv1aOffset) {
  return plumage::fnv1a(std::string_view(data, n), h);
}

void check_axis(const std::vector<double>& a, const char* name, bool cosine) {
  if (a.empty()) throw Error(std::string("reflection table: empty axis ") + name);
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i])) throw Error(std::string("reflection table: non-finite value on axis ") + name);
    if (i > 0 && !(a[i] > a[i - 1]))
      throw Error(std::string("reflection table: axis ") + name + " is not strictly ascending");
    if (cosine && (a[i] < 0.0 || a[i] > 1.0))
      throw Error(std::string("reflection table: axis ") + name + " outside [0, 1]");
  }
}

// A grid read from a file: finite, strictly increasing, within [lo, hi]; InputFileError naming
// the axis and index otherwise (the constructor's check_axis names no file).
void check_file_axis(const std::vector<double>& a, const char* axis, double lo, double hi, const std::string& file) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string at = std::string(axis) + "[" + std::to_string(i) + "]: " + std::to_string(a[i]);
    if (!std::isfinite(a[i]) || a[i] < lo || a[i] > hi)
      throw InputFileError(file, at + ", expected a finite value in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    if (i > 0 && !(a[i] > a[i - 1]))
      throw InputFileError(file, at + " after " + std::to_string(a[i - 1]) + ": the axis must be strictly increasing");
  }
}

double checked_scalar(double v, const char* field, const std::string& file) {
  if (!std::isfinite(v) || v < 0) throw InputFileError(file, std::string(field) + ": " + std::to_string(v) + ", expected a finite value >= 0");
  return v;
}

// Cubic Hermite (Catmull-Rom with non-uniform spacing) weights over up to four nodes.
struct Stencil {
  int idx[4] = {0, 0, 0, 0};
  double w[4] = {0, 0, 0, 0};
  int n = 0;
};

Stencil cubic_stencil(const std::vector<double>& x, double v) {
  Stencil s;
  const int n = static_cast<int>(x.size());
  if (n == 1 || v <= x.front()) {
    s.n = 1;
    s.idx[0] = 0;
    s.w[0] = 1.0;
    return s;
  }
  if (v >= x.back()) {
    s.n = 1;
    s.idx[0] = n - 1;
    s.w[0] = 1.0;
    return s;
  }
  const int i1 = static_cast<int>(std::upper_bound(x.begin(), x.end(), v) - x.begin()) - 1;
  const int i2 = i1 + 1;
  const double d = x[i2] - x[i1];
  const double t = (v - x[i1]) / d;
  const double h00 = 2 * t * t * t - 3 * t * t + 1, h10 = t * t * t - 2 * t * t + t;
  const double h01 = -2 * t * t * t + 3 * t * t, h11 = t * t * t - t * t;
  // Node list i0..i3 with fallbacks at the ends (one-sided slopes).
  double w0 = 0, w1 = h00, w2 = h01, w3 = 0;
  // slope m1 = (p2 − p0)/(x2 − x0)  or (p2 − p1)/(x2 − x1) at the start
  if (i1 > 0) {
    const double c = h10 * d / (x[i2] - x[i1 - 1]);
    w2 += c;
    w0 -= c;
  } else {
    w2 += h10;
    w1 -= h10;
  }
  // slope m2 = (p3 − p1)/(x3 − x1)  or (p2 − p1)/(x2 − x1) at the end
  if (i2 < n - 1) {
    const double c = h11 * d / (x[i2 + 1] - x[i1]);
    w3 += c;
    w1 -= c;
  } else {
    w2 += h11;
    w1 -= h11;
  }
  s.n = 0;
  auto push = [&](int i, double w) {
    if (w != 0.0) {
      s.idx[s.n] = i;
      s.w[s.n] = w;
      ++s.n;
    }
  };
  if (i1 > 0) push(i1 - 1, w0);
  push(i1, w1);
  push(i2, w2);
  if (i2 < n - 1) push(i2 + 1, w3);
  return s;
}

void add_scaled(JonesReflection& acc, const JonesReflection& v, double w) {
  acc.ss += w * v.ss;
  acc.sp += w * v.sp;
  acc.ps += w * v.ps;
  acc.pp += w * v.pp;
}

// Serialisation helpers (little-endian hosts only; the byte-order mark is checked on load).
void put_u32(std::string& b, std::uint32_t v) { b.append(reinterpret_cast<const char*>(&v), 4); }
void put_f64(std::string& b, double v) { b.append(reinterpret_cast<const char*>(&v), 8); }
void put_str(std::string& b, const std::string& s) {
  put_u32(b, static_cast<std::uint32_t>(s.size()));
  b.append(s);
}

class Reader {
 public:
  Reader(const std::string& b, std::string file) : b_(b), file_(std::move(file)) {}
  void need(std::size_t n) const {
    if (n > b_.size() - 8 || pos_ > b_.size() - 8 - n)
      throw InputFileError(file_, "truncated reflection table: " + std::to_string(n) + " bytes needed at byte " +
                                      std::to_string(pos_) + ", " + std::to_string(b_.size() - 8 - pos_) + " remain");
  }
  std::uint32_t u32() {
    need(4);
    std::uint32_t v;
    std::memcpy(&v, b_.data() + pos_, 4);
    pos_ += 4;
    return v;
  }
  double f64() {
    need(8);
    double v;
    std::memcpy(&v, b_.data() + pos_, 8);
    pos_ += 8;
    return v;
  }
  std::string str() {
    const std::uint32_t n = u32();
    if (n > (1u << 24)) throw InputFileError(file_, "corrupt string length " + std::to_string(n) + " at byte " + std::to_string(pos_ - 4));
    need(n);
    std::string s = b_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  std::size_t pos() const { return pos_; }

 private:
  const std::string& b_;
  std::string file_;
  std::size_t pos_ = 0;
};

std::string hex64(std::uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace

TableGrid TableGrid::uniform(double lo, double hi, int n_lambda, int n_theta, int n_phi) {
  if (n_lambda < 1 || n_theta < 1 || n_phi < 1) throw Error("table grid: every axis needs >= 1 node");
  TableGrid g;
  for (int i = 0; i < n_lambda; ++i)
    g.lambda_nm.push_back(n_lambda == 1 ? lo : lo + (hi - lo) * i / (n_lambda - 1));
  for (int i = 1; i <= n_theta; ++i) g.cos_theta.push_back(static_cast<double>(i) / n_theta);
  for (int i = 1; i <= n_phi; ++i) g.cos_phi.push_back(static_cast<double>(i) / n_phi);
  return g;
}

ReflectionTable::ReflectionTable(TableGrid grid, TableMetadata meta)
    : grid_(std::move(grid)), meta_(std::move(meta)) {
  check_axis(grid_.lambda_nm, "lambda_nm", false);
  check_axis(grid_.cos_theta, "cos_theta", true);
  check_axis(grid_.cos_phi, "cos_phi", true);
  data_.assign(grid_.lambda_nm.size() * grid_.cos_theta.size() * grid_.cos_phi.size(),
               JonesReflection{});
  if (grid_.cos_theta.front() > 0.0) ext_cos_theta_.push_back(0.0);
  ext_cos_theta_.insert(ext_cos_theta_.end(), grid_.cos_theta.begin(), grid_.cos_theta.end());
  if (grid_.cos_phi.front() > 0.0) ext_cos_phi_.push_back(0.0);
  ext_cos_phi_.insert(ext_cos_phi_.end(), grid_.cos_phi.begin(), grid_.cos_phi.end());
}

JonesReflection ReflectionTable::query_first_quadrant(double lambda_nm, double ct, double cp) const {
  // Axes extended by the analytic grazing node at cos = 0 when the table does not hold it.
  const bool ext_t = grid_.cos_theta.front() > 0.0, ext_p = grid_.cos_phi.front() > 0.0;
  const Stencil st = cubic_stencil(ext_cos_theta_, ct), sp = cubic_stencil(ext_cos_phi_, cp);

  // Linear in λ (clamped).
  const auto& L = grid_.lambda_nm;
  std::size_t l0 = 0, l1 = 0;
  double wl1 = 0.0;
  if (lambda_nm <= L.front()) {
    l0 = l1 = 0;
  } else if (lambda_nm >= L.back()) {
    l0 = l1 = L.size() - 1;
  } else {
    l1 = static_cast<std::size_t>(std::upper_bound(L.begin(), L.end(), lambda_nm) - L.begin());
    l0 = l1 - 1;
    wl1 = (lambda_nm - L[l0]) / (L[l1] - L[l0]);
  }
  const JonesReflection g = grazing_jones();
  JonesReflection out;
  for (int a = 0; a < st.n; ++a) {
    for (int b = 0; b < sp.n; ++b) {
      const double w = st.w[a] * sp.w[b];
      const int it = st.idx[a] - (ext_t ? 1 : 0), ip = sp.idx[b] - (ext_p ? 1 : 0);
      if (it < 0 || ip < 0) {
        add_scaled(out, g, w);
        continue;
      }
      add_scaled(out, at(l0, it, ip), w * (1.0 - wl1));
      if (wl1 != 0.0) add_scaled(out, at(l1, it, ip), w * wl1);
    }
  }
  return out;
}

double largest_singular_value(const JonesReflection& j) {
  // Largest eigenvalue of the Hermitian M = J^H J, in the form without cancellation:
  // λ_max = (m11 + m22)/2 + sqrt(((m11 − m22)/2)² + |m12|²).
  const double m11 = std::norm(j.ss) + std::norm(j.ps), m22 = std::norm(j.sp) + std::norm(j.pp);
  const Complex m12 = std::conj(j.ss) * j.sp + std::conj(j.ps) * j.pp;
  const double half = 0.5 * (m11 - m22);
  return std::sqrt(0.5 * (m11 + m22) + std::sqrt(half * half + std::norm(m12)));
}

JonesReflection ReflectionTable::query(double lambda_nm, double theta_rad, double phi_local_rad) const {
  if (data_.empty()) throw Error("reflection table: query on an empty table");
  const double ct = std::cos(theta_rad), cp = std::cos(phi_local_rad);
  if (ct < -1e-12 || cp < -1e-12) return {};            // back-facing
  if (ct < 1e-12 || cp < 1e-12) return grazing_jones();  // exact grazing limit
  JonesReflection r = query_first_quadrant(lambda_nm, std::min(ct, 1.0), std::min(cp, 1.0));
  // Passivity: the cubic interpolation toward the grazing node (|r| = 1) can overshoot; a
  // passive surface reflects at most what it receives, i.e. σ_max(J) ≤ 1 in this
  // power-normalised (E·ŝ, η0H·ŝ) basis. An overshoot is scaled back to 1.
  const double sigma = largest_singular_value(r);
  if (sigma > 1.0) {
    const double k = 1.0 / sigma;
    r.ss *= k, r.sp *= k, r.ps *= k, r.pp *= k;
  }
  if (std::sin(phi_local_rad) < 0.0) {  // mirror x → −x: J → D J D, D = diag(−1, 1)
    r.sp = -r.sp;
    r.ps = -r.ps;
  }
  return r;
}

std::string ReflectionTable::content_hash() const {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const auto* axis : {&grid_.lambda_nm, &grid_.cos_theta, &grid_.cos_phi}) {
    const std::uint32_t n = static_cast<std::uint32_t>(axis->size());
    h = fnv1a(reinterpret_cast<const char*>(&n), 4, h);
    h = fnv1a(reinterpret_cast<const char*>(axis->data()), axis->size() * sizeof(double), h);
  }
  h = fnv1a(reinterpret_cast<const char*>(data_.data()), data_.size() * sizeof(JonesReflection), h);
  return hex64(h);
}

void ReflectionTable::save(const std::filesystem::path& file) const {
  static_assert(sizeof(JonesReflection) == 8 * sizeof(double));
  std::string b;
  b.append(kMagic, 8);
  put_u32(b, kVersion);
  put_u32(b, kByteOrder);
  put_u32(b, static_cast<std::uint32_t>(grid_.lambda_nm.size()));
  put_u32(b, static_cast<std::uint32_t>(grid_.cos_theta.size()));
  put_u32(b, static_cast<std::uint32_t>(grid_.cos_phi.size()));
  put_str(b, kUnits);
  put_str(b, meta_.producer);
  put_str(b, meta_.crystal);
  put_str(b, meta_.config_hash);
  put_str(b, meta_.notes);
  put_str(b, content_hash());
  put_f64(b, meta_.period_nm);
  put_f64(b, meta_.resolution_nm);
  for (const auto* axis : {&grid_.lambda_nm, &grid_.cos_theta, &grid_.cos_phi})
    for (double v : *axis) put_f64(b, v);
  b.append(reinterpret_cast<const char*>(data_.data()), data_.size() * sizeof(JonesReflection));
  const std::uint64_t sum = fnv1a(b.data(), b.size());
  b.append(reinterpret_cast<const char*>(&sum), 8);
  write_file_atomically(file, [&](std::ostream& os) { os.write(b.data(), static_cast<std::streamsize>(b.size())); },
                        true);
}

ReflectionTable ReflectionTable::load(const std::filesystem::path& file) {
  const std::string name = file.string();
  const std::string b = read_input_file(file, "reflection table");
  const auto fail = [&](const std::string& what) { throw InputFileError(name, what); };
  if (b.size() < 16 || std::memcmp(b.data(), kMagic, 8) != 0) fail("not a PLMRTAB reflection table (bad magic)");
  std::uint64_t stored;
  std::memcpy(&stored, b.data() + b.size() - 8, 8);
  if (fnv1a(b.data(), b.size() - 8) != stored) fail("checksum mismatch (reflection table corrupt or truncated)");
  Reader rr(b, name);
  for (int i = 0; i < 2; ++i) rr.u32();  // magic
  const std::uint32_t version = rr.u32();
  if (version != kVersion) fail("reflection table version " + std::to_string(version) + " not supported");
  if (rr.u32() != kByteOrder) fail("foreign byte order");
  const std::uint32_t nl = rr.u32(), nt = rr.u32(), np = rr.u32();
  rr.str();  // units
  TableMetadata meta;
  meta.producer = rr.str();
  meta.crystal = rr.str();
  meta.config_hash = rr.str();
  meta.notes = rr.str();
  const std::string hash = rr.str();
  meta.period_nm = checked_scalar(rr.f64(), "period_nm", name);
  meta.resolution_nm = checked_scalar(rr.f64(), "resolution_nm", name);
  // The sizes against the bytes the file holds, before anything of their size is allocated:
  // the axes, then nl·nt·np Jones entries and the checksum, exactly.
  rr.need((std::uint64_t{nl} + nt + np) * 8);
  const std::uint64_t left = b.size() - 8 - rr.pos() - (std::uint64_t{nl} + nt + np) * 8;
  const std::uint64_t entries = std::uint64_t{nl} * nt * np;  // < 2^96 would overflow: bound each first
  if (nl == 0 || nt == 0 || np == 0 || entries / nl / nt != np || entries > left / sizeof(JonesReflection) ||
      entries * sizeof(JonesReflection) != left)
    fail("size mismatch: " + std::to_string(nl) + " x " + std::to_string(nt) + " x " + std::to_string(np) +
         " entries of " + std::to_string(sizeof(JonesReflection)) + " bytes, but " + std::to_string(left) +
         " bytes follow the axes");
  TableGrid g;
  for (std::uint32_t i = 0; i < nl; ++i) g.lambda_nm.push_back(rr.f64());
  for (std::uint32_t i = 0; i < nt; ++i) g.cos_theta.push_back(rr.f64());
  for (std::uint32_t i = 0; i < np; ++i) g.cos_phi.push_back(rr.f64());
  check_file_axis(g.lambda_nm, "lambda_nm", 1e-9, kFileMaxWavelengthNm, name);
  check_file_axis(g.cos_theta, "cos_theta", 0.0, 1.0, name);
  check_file_axis(g.cos_phi, "cos_phi", 0.0, 1.0, name);
  ReflectionTable t(std::move(g), std::move(meta));
  const std::size_t bytes = t.data_.size() * sizeof(JonesReflection);
  std::memcpy(static_cast<void*>(t.data_.data()), b.data() + rr.pos(), bytes);
  for (std::size_t k = 0; k < t.data_.size(); ++k) {
    const JonesReflection& j = t.data_[k];
    for (const Complex* c : {&j.ss, &j.sp, &j.ps, &j.pp})
      if (!std::isfinite(c->real()) || !std::isfinite(c->imag()))
        fail("Jones entry " + std::to_string(k) + " (byte " + std::to_string(rr.pos() + k * sizeof(JonesReflection)) +
             "): not finite");
  }
  if (t.content_hash() != hash) fail("content hash mismatch");
  return t;
}

}  // namespace plumage
