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
// and, for the noise identification (noise_identification.h), the lag-1 sums of the
// non-overlapping averages of the rate ȳ_j = (X_{jm} - X_{(j-1)m}) / m, j = 1..floor(N/m), and of
// their first and second differences (AveragedFrequencySeries, over its bounded prefix of 2^16
// averages): a few values per m-th anchor, so the averaged series is never stored, whatever N and m.
// The IEEE Std 952-1997 Annex C / IEEE Std 1139 overlapping Allan variance of the reference
// (section 3) is OADEV. The engine uses worker threads (std::thread) for the factors and runs the
// caller's reading of the next chunk in parallel with the work on the last one.
//
// Memory: the ring holds (3 or 2) m + 2 blocks phase values for the largest factor m it serves.
// With a ring_capacity_limit, the factors whose span exceeds it are left to a second pass in
// finish(): it re-reads the record through the caller's SampleReader, in segments of anchors k, into
// windows of the phase around k, k - m, k - 2m, k - 3m, each integrated again from a checkpoint of
// the first pass (the Neumaier state after every block), block by block as the first pass did, so
// the phase values are bit for bit those of the first pass. Overlapping estimators need the phase
// at every offset, so decimated data would not give the same sums; re-reading costs about 5 (N - m) samples per deferred factor, and at most a
// few octave factors exceed any limit above N/2 phase values.
//
// Speed (issue 15): the reader writes the samples into the ring (room/commit; push() copies them
// there) and each whole block is integrated there in place, in four Neumaier chains side by side in
// the lanes of a vector (one chain cost an FP-add latency per sample), the chains' carries added
// after; the cut depends on the block only, so the phase is the same bits whatever the chunks
// pushed or the thread count, and the second pass repeats it. The workers take contiguous ranges of
// the factors (and TOTDEV's ends in pieces) and sweep each block in sub-blocks of 16384 anchors,
// every factor of the range per sub-block: on an octave grid the lag 2m of factor m is the lag m of
// the next factor, so a sub-block of a far lag comes from DRAM once and serves two factors, and
// small lags come from L1/L2. Each term is a few flops on 3 or 4 phase streams; the sums of the
// overlapping averages (B1 ratio) ride in the same loops, and the non-overlapping averages are fed
// to the noise identification in batches whose sums stay in registers. Third differences add the
// lag 3m: MDEV/HDEV/OHDEV move about twice the data of OADEV per tau. The MDEV window w_k = w_{k-1}
// + h_k runs as sixteen chains over parts of each run, each from zero; a part's sum of squares is
// then taken about the window before it.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "inertest/allan/lag1_sums.h"

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

// Raw sums of one averaging factor, in (input unit * samples)^2, and their numbers of terms. The
// OADEV sums are always there (every estimator set computes them), the others for the estimators
// asked for (0 terms otherwise).
struct AllanSums {
  std::size_t averaging_factor = 0;  // m
  std::array<double, 6> sum_of_squares{};      // indexed by Estimator
  std::array<std::size_t, 6> term_count{};     // indexed by Estimator
  // The averages of the rate over m samples (offset removed, input unit) and their differences.
  AveragedFrequencySeries averages;
  // The sample variance of the N - m + 1 overlapping averages (X_k - X_{k-m}) / m, k = m .. N, in
  // the input unit squared: the B1 ratio of the overlapping estimators needs it, so it is summed
  // only where fewer than kLag1MinimumAverages non-overlapping averages remain (NaN elsewhere).
  double overlapping_average_variance = std::numeric_limits<double>::quiet_NaN();
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
  // Most phase values the ring may hold (0: no limit); larger factors go to the second pass.
  std::size_t ring_capacity_limit = 0;
};

// Random access to the rate record for the second pass: fills `out` with samples
// [first, first + out.size()) (0-based), exactly the values pushed in the first pass.
using SampleReader = std::function<void(std::size_t first, std::span<double> out)>;

class AllanEngine {
 public:
  // sample_count: N, the number of rate samples that will be pushed; offset: subtracted from every
  // sample (the record's mean or an estimate of it, so that the integrated phase stays near zero). Throws Error when a
  // factor is not supported by N samples.
  AllanEngine(std::size_t sample_count, double offset, AllanEngineOptions options);
  // The engine in place, for a record already in memory: the N samples (which must outlive the
  // engine) become the phase, X_k where sample k was, integrated and handed to the workers block by
  // block as push() would; no ring is allocated and no sample copied (a ring of N values is that
  // much fresh memory for the kernel to clear, per channel). The sums equal those of pushing the
  // samples to within rounding (X_0 is kept apart, which cuts the first runs of each factor where a
  // ring keeps them whole). ring_capacity_limit does not apply. Call finish() next; push() throws.
  AllanEngine(std::span<double> samples, double offset, AllanEngineOptions options);
  ~AllanEngine();
  AllanEngine(const AllanEngine&) = delete;
  AllanEngine& operator=(const AllanEngine&) = delete;

  // Feeds the next samples, in order, in chunks of any size. Throws Error past N samples.
  void push(std::span<const double> samples);
  // push() without the copy, for a reader that can write the samples where they go: room() is
  // where the next samples go (at least one slot, up to the end of a block), and commit(count)
  // says that its first `count` slots hold the next samples. Throws Error past N samples.
  std::span<double> room();
  void commit(std::size_t count);
  // Completes the sums after exactly N samples, running the second pass through `reader` when some
  // factors were deferred; throws Error when fewer were pushed, or when a second pass is needed and
  // there is no reader. Sums are ordered by averaging factor.
  std::vector<AllanSums> finish(const SampleReader& reader = {});

  // X_N = the sum of (y - offset) over the record, after finish(): the record's mean is
  // offset + X_N / N, so a caller that streams the record once can pass a provisional offset (the
  // mean of its first chunk) and learn the mean at the end. No estimator depends on the offset
  // (a constant in the rate is a line in the phase, which second and third differences, the
  // reflections of TOTDEV and the shifted sums of the noise identification cancel), only the
  // rounding does, and that stays small while the offset is near the mean.
  double phase_total() const;
  // Bytes held by the ring buffer of the phase (for memory accounting).
  std::size_t ring_bytes() const;
  // Factors left to the second pass (those whose span exceeds ring_capacity_limit).
  std::size_t deferred_factor_count() const;

 private:
  AllanEngine(std::size_t sample_count, double offset, AllanEngineOptions options, double* samples_in_place);
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace inertest
