// The streaming engine behind every Allan-family estimator: it integrates rate samples into the
// phase (angle) X_k = sum_{i<=k} (y_i - offset), k = 0..N with X_0 = 0, keeps only a ring buffer of
// the last 3*m_max + 2*block values of X shared by all averaging factors, and accumulates, for each
// factor m, the sums of squares that NIST SP 1065 (2008) defines each estimator by (phase form,
// x = tau0 * X):
//   OADEV  eq. (11): a_k = X_k - 2 X_{k-m} + X_{k-2m},          k = 2m..N            (N+1-2m terms)
//   ADEV   eq. (7) : the same a_k at k = 2m, 3m, ... (k a multiple of m)          (floor(N/m)-1 terms)
//   OHDEV  eq. (17): h_k = X_k - 3X_{k-m} + 3X_{k-2m} - X_{k-3m} = a_k - a_{k-m}, k = 3m..N
//   HDEV   eq. (16): the same h_k at multiples of m                              (floor(N/m)-2 terms)
//   MDEV   eq. (14): w_k = sum_{t=k-m+1}^{k} a_t,                k = 3m-1..N        (N+2-3m terms)
//   TOTDEV eq. (25): a at every centre c = 1..N-1 of the record reflected about both ends,
//                    X*_{-j} = 2X_0 - X_j, X*_{N+j} = 2X_N - X_{N-j}                     (N-1 terms)
// The IEEE Std 952-1997 Annex C / IEEE Std 1139 overlapping Allan variance of the reference
// (section 3) is OADEV. The engine uses worker threads (std::thread) for the factors and runs the
// caller's reading of the next chunk in parallel with the work on the last one.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace inertest {

enum class Estimator { kAdev, kOadev, kMdev, kHdev, kOhdev, kTotdev };
inline constexpr std::array<Estimator, 6> kAllEstimators = {Estimator::kAdev,  Estimator::kOadev, Estimator::kMdev,
                                                            Estimator::kHdev,  Estimator::kOhdev, Estimator::kTotdev};

// "adev", "oadev", "mdev", "hdev", "ohdev", "totdev".
std::string_view estimator_name(Estimator estimator);
// Parses one name; throws Error listing the names.
Estimator parse_estimator(std::string_view name);

// A set of estimators (a bit mask over Estimator).
class EstimatorSet {
 public:
  EstimatorSet() = default;
  static EstimatorSet all();
  // A comma list of names, or "all"; throws Error.
  static EstimatorSet parse(std::string_view text);
  void insert(Estimator estimator) { bits_ |= bit(estimator); }
  bool contains(Estimator estimator) const { return (bits_ & bit(estimator)) != 0; }
  bool empty() const { return bits_ == 0; }
  std::vector<Estimator> members() const;
  // Whether any estimator needs third differences (MDEV, HDEV, OHDEV), i.e. a span of 3m.
  bool needs_third_differences() const;

 private:
  static unsigned bit(Estimator estimator) { return 1u << static_cast<unsigned>(estimator); }
  unsigned bits_ = 0;
};

// The largest averaging factor every estimator of the set supports on N rate samples (at least one
// term each): N/2 for ADEV, OADEV and TOTDEV (tau <= T/2), N/3 for HDEV, OHDEV and MDEV.
std::size_t largest_averaging_factor(std::size_t sample_count, const EstimatorSet& estimators);

// Raw sums of one averaging factor, in (input unit * samples)^2, and their numbers of terms.
struct AllanSums {
  std::size_t averaging_factor = 0;  // m
  std::array<double, 6> sum_of_squares{};      // indexed by Estimator
  std::array<std::size_t, 6> term_count{};     // indexed by Estimator
  double sum(Estimator e) const { return sum_of_squares[static_cast<std::size_t>(e)]; }
  std::size_t terms(Estimator e) const { return term_count[static_cast<std::size_t>(e)]; }
  // The variance of the estimator in the input unit squared (NIST SP 1065 normalisations: the
  // tau0 of x = tau0 * X cancels): OADEV/ADEV S/(2 m^2 n), OHDEV/HDEV S/(6 m^2 n), MDEV S/(2 m^4 n),
  // TOTDEV S/(2 m^2 (N-1)).
  double variance(Estimator e) const;
};

struct AllanEngineOptions {
  std::vector<std::size_t> averaging_factors;  // sorted, distinct, each <= largest_averaging_factor
  EstimatorSet estimators = EstimatorSet::all();
  std::size_t worker_count = 2;       // threads; 1 runs everything on the caller's thread
  std::size_t block_size = 1u << 15;  // samples per unit of work
};

class AllanEngine {
 public:
  // sample_count: N, the number of rate samples that will be pushed; offset: subtracted from every
  // sample (the record's mean, so that the integrated phase stays near zero). Throws Error when a
  // factor is not supported by N samples.
  AllanEngine(std::size_t sample_count, double offset, AllanEngineOptions options);
  ~AllanEngine();
  AllanEngine(const AllanEngine&) = delete;
  AllanEngine& operator=(const AllanEngine&) = delete;

  // Feeds the next samples, in order, in chunks of any size. Throws Error past N samples.
  void push(std::span<const double> samples);
  // Completes the sums after exactly N samples; throws Error when fewer were pushed.
  std::vector<AllanSums> finish();

  // Bytes held by the ring buffer of the phase (for memory accounting).
  std::size_t ring_bytes() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace inertest
