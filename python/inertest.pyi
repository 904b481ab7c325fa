"""Type stubs of the inertest Python module (pybind11).

inertest: test data processing for gyroscopes and accelerometers (GJB 2426A-2004, IEEE Std 952-1997).
Procedures take numpy arrays and return results whose attributes are the JSON names of the CLI's
--json output (every figure a Figure with value, unit and uncertainty; to_dict() is that JSON).
Bad input raises inertest.Error, a ValueError with the CLI's message.
"""

from typing import Any, Optional, Sequence, Union

import numpy
import numpy.typing

ArrayLike = numpy.typing.ArrayLike
FloatArray = numpy.typing.NDArray[numpy.float64]
IntArray = numpy.typing.NDArray[numpy.int64]

__version__: str
CITATIONS: dict[str, str]  # 'misalignment', 'centrifuge': the papers by title, authors, institution
DRIFT_TERMS: tuple[str, ...]  # 'D_F', 'D_I', ... 'D_OS', the order of q in eq. (13) of the centrifuge paper

class Error(ValueError):
    """Bad input or options: the message is what the CLI prints after 'inertest: error: '."""

    message: str  # without the location
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]

# core ------------------------------------------------------------------------------------------

class Figure:
    """A reported figure: value, unit and, where known, its 1-sigma uncertainty in the same unit."""

    value: float
    unit: str
    uncertainty: Optional[float]
    def __init__(self, value: float, unit: str = "1", uncertainty: Optional[float] = None) -> None: ...
    def to(self, unit: str) -> Figure:
        """The same figure (uncertainty too) in another unit of the same dimension."""
    def to_dict(self) -> dict[str, Any]: ...
    def __float__(self) -> float: ...

class Record:
    """A JSON object seen through attributes: record.name is its member 'name'. A member
    {'value', 'unit'[, 'uncertainty']} is a Figure, another object a Record, an array of numbers a
    numpy array, any other array a list."""

    def __getattr__(self, name: str) -> Any: ...
    def __getitem__(self, name: str) -> Any: ...
    def __contains__(self, name: str) -> bool: ...
    def keys(self) -> list[str]: ...
    def to_dict(self) -> dict[str, Any]:
        """The JSON as plain Python objects: equal to json.loads() of the CLI's --json output."""
    def json(self, indent: int = -1) -> str: ...

class Result(Record):
    def report(self) -> str:
        """The readable multi-line summary the CLI prints without --json."""

def convert(value: Union[float, ArrayLike], from_unit: str, to_unit: str) -> Union[float, FloatArray]:
    """Converts a number or an array between units of one dimension ('deg/h', 'rad/s', 'deg/sqrt(h)', ...)."""

# io --------------------------------------------------------------------------------------------

class TextTable:
    """Numeric columns of a text record; table['name'] is a float64 array owning the reader's buffer."""

    source: str
    names: list[str]
    columns: list[FloatArray]
    row_lines: numpy.typing.NDArray[numpy.uint64]
    first_data_line: int
    def __len__(self) -> int: ...
    def __getitem__(self, key: Union[str, int]) -> FloatArray: ...
    def to_dict(self) -> dict[str, FloatArray]: ...

def read_text_table(
    path: str,
    columns: Optional[Sequence[Union[str, int]]] = None,
    delimiter: Optional[str] = None,
    header: Optional[bool] = None,
    comment: str = "#",
    minimum_rows: int = 1,
    record_row_lines: bool = True,
) -> TextTable:
    """Numeric columns of a text record (CSV, TSV, ';' or whitespace); columns by name or 1-based position."""

def read_binary_record(
    path: str, format: str = "f64", channels: int = 1, channel: int = 0
) -> FloatArray:
    """One channel of a raw binary record ('f64', 'f32', 'i32', 'i16' + optional 'le'/'be')."""

# procedures (GJB 2426A-2004, IEEE Std 952-1997) -------------------------------------------------

class ScaleFactorResult(Result):
    """GJB 2426A-2004 5.8.1-5.8.3, eqs. (1)-(11)."""

    procedure: str
    clause: str
    scale_factor: Figure  # K, eq. (5)
    zero_offset: Figure  # F0, eq. (6)
    nonlinearity: Figure  # Kn, eq. (9), ppm
    asymmetry: Figure  # Ka, eqs. (10)-(11), ppm
    scale_factor_positive: Figure
    scale_factor_negative: Figure
    static_output_start: Figure
    static_output_end: Figure
    fit_residual_rms: Figure
    nonlinearity_curve: list[Record]  # rate, deviation (eq. 8)
    warnings: list[str]

def scale_factor(
    rate: ArrayLike,
    output: ArrayLike,
    *,
    rate_unit: str = "deg/s",
    output_unit: str = "1",
    recommended_rates_per_direction: int = 11,
    source: Optional[str] = None,
) -> ScaleFactorResult:
    """Scale factor, nonlinearity, asymmetry: GJB 2426A-2004 5.8.1-5.8.3, eqs. (1)-(11); IEEE Std 952-1997 clause 13 (A.12)."""

class BiasResult(Result):
    """GJB 2426A-2004 5.12.1 eq. (19), 5.12.2 eq. (20), 5.12.5.4.1 eqs. (23)-(24)."""

    bias: Figure  # deg/h
    bias_stability: list[Record]  # smoothing_s, value, unit
    noise_equivalent_rate: Figure
    random_walk_coefficient: Figure  # deg/sqrt(h)

def bias(
    output: ArrayLike,
    *,
    sample_rate_hz: float,
    scale_factor: Optional[float] = None,
    input_in_deg_h: bool = False,
    output_unit: str = "1",
    smoothing_s: Sequence[float] = (1.0, 10.0, 100.0),
    random_walk: bool = True,
    latitude_deg: Optional[float] = None,
    heading_deg: float = 0.0,
    elevation_deg: float = 0.0,
    source: Optional[str] = None,
) -> BiasResult:
    """Bias (GJB 2426A-2004 5.12.1 eq. 19), bias stability (5.12.2 eq. 20), random walk (5.12.5.4.1 eqs. 23-24)."""

class MaximumInputRateResult(Result):
    """GJB 2426A-2004 5.9."""

    maximum_input_rate: Figure
    nonlinearity: Figure  # ppm
    nonlinearity_limit: Figure  # ppm

def maximum_input_rate(
    rate: ArrayLike, output: ArrayLike, *, nonlinearity_limit_ppm: float, rate_unit: str = "deg/s", output_unit: str = "1"
) -> MaximumInputRateResult:
    """Maximum input rate meeting the nonlinearity requirement: GJB 2426A-2004 5.9 (eqs. 1-9 per range)."""

class ScaleFactorRepeatabilityResult(Result):
    """GJB 2426A-2004 5.8.4, eq. (12)."""

    scale_factor_repeatability: Figure  # ppm

def scale_factor_repeatability(scale_factors: ArrayLike, *, unit: str = "1", minimum_runs: int = 6) -> ScaleFactorRepeatabilityResult:
    """Scale factor repeatability Kr: GJB 2426A-2004 5.8.4, eq. (12)."""

class BiasRepeatabilityResult(Result):
    """GJB 2426A-2004 5.12.3, eq. (21)."""

    bias_repeatability: Figure  # deg/h

def bias_repeatability(biases_deg_h: ArrayLike) -> BiasRepeatabilityResult:
    """Bias repeatability Br: GJB 2426A-2004 5.12.3, eq. (21)."""

class BiasTemperatureSensitivityResult(Result):
    """GJB 2426A-2004 5.12.4, eq. (22)."""

    bias_temperature_sensitivity: Figure  # deg/h/degC

def bias_temperature_sensitivity(
    temperature_degC: ArrayLike, bias_deg_h: ArrayLike, *, room_temperature_degC: Optional[float] = None
) -> BiasTemperatureSensitivityResult:
    """Bias temperature sensitivity Bt: GJB 2426A-2004 5.12.4, eq. (22)."""

class BandwidthResult(Result):
    """GJB 2426A-2004 5.13-5.14, eqs. (32)-(46)."""

    bandwidth: Figure  # Hz
    delay: Figure  # s
    dc_gain: Figure
    time_constant: Figure  # s
    polarity: int  # -1: a negative scale factor's 180 deg removed from every phase before eqs. (43)-(46)
    bode: list[Record]

def bandwidth_and_delay(
    frequency_hz: ArrayLike, gain: ArrayLike, phase_deg: ArrayLike, *, minimum_frequencies: int = 10
) -> BandwidthResult:
    """Bandwidth (GJB 2426A-2004 5.13, eqs. 32-41) and output delay (5.14, eqs. 42-46)."""

class ThresholdResult(Result):
    """GJB 2426A-2004 5.10, eqs. (14)-(17); the 50 % criterion of IEEE Std 952-1997 by default."""

    threshold: Figure  # deg/h
    method: int
    criterion_denominator: str  # "expected" (IEEE Std 952-1997) or "measured" (GJB eq. 15 as printed)
    criterion: str
    branches: list[Record]

def threshold_rate_table(
    rate: ArrayLike,
    output: ArrayLike,
    *,
    scale_factor: float,
    rate_unit: str = "deg/s",
    zero_output: Optional[float] = None,
    criterion_denominator: str = "expected",
) -> ThresholdResult:
    """Threshold by method 1 (rate table), GJB 2426A-2004 5.10.4.1; criterion relative to the expected output."""

class InputAxisMisalignmentResult(Result):
    """GJB 2426A-2004 5.15, eqs. (47)-(50)."""

    misalignment: Figure  # arcsec

def input_axis_misalignment(
    output_positive: ArrayLike,
    output_negative: ArrayLike,
    *,
    scale_factor: float,
    rate: float,
    rate_unit: str = "deg/s",
    output_unit: str = "1",
) -> InputAxisMisalignmentResult:
    """Input-axis misalignment from 2 or 4 positions: GJB 2426A-2004 5.15, eqs. (47)-(50)."""

# allan (GJB 2426A-2004 5.12.5.4.2, IEEE Std 952-1997 Annex C, NIST SP 1065) ----------------------

class AllanResult(Result):
    """Allan deviations with chi-squared bounds and the noise terms (GJB eq. 30-31, IEEE 952 C.1)."""

    procedure: str
    standard: str
    sample_count: int
    sample_rate_hz: float
    record_length: Figure  # s
    input_unit: str
    mean: Figure
    tau_grid: str
    confidence_level: float
    tau: FloatArray  # s
    averaging_factor: IntArray
    noise_type: list[str]  # per tau, dominant noise identified for the Allan variance (NIST SP 1065 5.6)
    alpha: IntArray  # the same as S_y(f) ~ f^alpha: 2 white PM, 1 flicker PM, 0 white FM, -1 flicker FM, -2 random walk FM
    # One Record per estimator asked for (adev, oadev, mdev, hdev, ohdev, totdev): unit, the numpy
    # arrays values, lower, upper (confidence bounds), edf, terms, alpha (per tau, the noise its edf
    # assumes), and the lists noise_type and noise_identification ("lag1_autocorrelation", "b1_ratio",
    # "b1_ratio_and_rn", "shorter_tau" or "not_identified").
    adev: Record
    oadev: Record
    mdev: Record
    hdev: Record
    ohdev: Record
    totdev: Record
    # quantization, angle_random_walk (= random_walk_coefficient, GJB eq. 31), bias_instability,
    # rate_random_walk, rate_ramp (Figures; identified False with an upper_bound when not measured),
    # fit (GJB eq. 30: coefficients, reduced_chi_squared, verdict, fit_range), slope_method; None when not fitted.
    noise: Optional[Record]
    warnings: list[str]

def allan_variance(
    rate: ArrayLike,
    *,
    sample_rate_hz: float,
    input_unit: str = "deg/h",
    taus: Union[str, Sequence[float], FloatArray] = "octave",  # a grid name or taus in s
    estimators: str = "all",
    scale: float = 1.0,
    confidence: float = 0.6826894921370859,
    worker_count: int = 2,
    fit_range: Optional[tuple[float, float]] = None,
) -> AllanResult:
    """ADEV, OADEV, MDEV, HDEV, OHDEV, TOTDEV and the noise terms of rate samples in memory."""

def allan_variance_of_file(
    path: str,
    *,
    sample_rate_hz: float,
    format: str = "auto",  # auto, csv, f64, f32, mat, hdf5, tdms
    column: Optional[str] = None,
    input_unit: str = "deg/h",
    taus: Union[str, Sequence[float], FloatArray] = "octave",  # a grid name or taus in s
    estimators: str = "all",
    scale: float = 1.0,
    confidence: float = 0.6826894921370859,
    worker_count: int = 2,
    fit_range: Optional[tuple[float, float]] = None,
) -> AllanResult:
    """The same on a record streamed from a file, as the CLI's allan command."""

def read_rate_record(
    path: str, format: str = "auto", column: Optional[str] = None
) -> FloatArray: ...
def fit_noise_terms(
    tau_s: ArrayLike,
    variance: ArrayLike,
    edf: ArrayLike,
    input_unit: str = "deg/h",
    *,
    fit_range: Optional[tuple[float, float]] = None,
    sample_count: int = 0,
    sample_interval_s: float = 0.0,
) -> Record:
    """Non-negative GLS of sigma^2 = sum A_p tau^p (GJB 2426A-2004 eq. 30), then Q, N, B, K, R (IEEE 952 C.1).
    A term held at zero has identified False and an upper_bound; fit has reduced_chi_squared, verdict and
    fit_range (tau_min_s, tau_max_s, chosen_by, reason)."""

def read_noise_slopes(tau_s: ArrayLike, deviation: ArrayLike, edf: ArrayLike, input_unit: str = "deg/h") -> Record: ...

# misalignment (the misalignment paper, CITATIONS["misalignment"]) --------------------------------

class GyroMisalignmentResult(Result):
    delta_theta_y0: Figure  # arcsec
    delta_theta_x0: Figure
    delta_theta_y1: Figure
    delta_theta_y2: Figure
    delta_theta_z2: Figure
    misalignment: Figure
    by_rate: list[Record]

class AccelerometerMisalignmentResult(Result):
    delta_theta_y2: Figure  # arcsec
    delta_theta_z2: Figure
    misalignment: Figure
    by_run: list[Record]

def gyro_misalignment(
    alpha_deg: ArrayLike,
    beta_deg: ArrayLike,
    rate_dps: ArrayLike,
    output: ArrayLike,
    *,
    scale_factor: float,
    output_unit: str = "1",
    line: Optional[ArrayLike] = None,
    source: Optional[str] = None,
) -> GyroMisalignmentResult:
    """Gyro misalignment separation on a rate table, least squares on V(+) - V(-) (the misalignment paper)."""

def accelerometer_misalignment(
    beta_deg: ArrayLike,
    output: ArrayLike,
    *,
    scale_factor: float,
    run: Optional[ArrayLike] = None,
    output_unit: str = "1",
    line: Optional[ArrayLike] = None,
    source: Optional[str] = None,
) -> AccelerometerMisalignmentResult:
    """Accelerometer misalignment by the multi-position gravity test (the misalignment paper)."""

def read_gyro_misalignment_positions(path: str) -> dict[str, Any]:
    """The keyword arguments of gyro_misalignment (arrays, line, source) from a means CSV."""

def read_gyro_misalignment_records(listing_path: str) -> dict[str, Any]: ...
def read_accelerometer_misalignment_positions(path: str) -> dict[str, Any]: ...
def whole_revolution_mean_by_angle(table_angle_deg: ArrayLike, output: ArrayLike) -> Record: ...
def whole_revolution_mean_by_time(time_s: ArrayLike, output: ArrayLike, rate_dps: float) -> Record: ...
def four_position_misalignment(
    v_0: float, v_90: float, v_180: float, v_270: float, scale_factor: float
) -> tuple[float, float]: ...
def five_position_misalignment(
    plus: Sequence[float], minus: Sequence[float], scale_factor: float, rate_dps: float
) -> tuple[float, float, float, float, float]: ...

# centrifuge (the centrifuge paper, CITATIONS["centrifuge"]) --------------------------------------

class HarmonicFit:
    amplitudes: list[float]  # k0, k1c, k1s, k2c, k2s
    residual_rms: float
    sample_count: int
    revolutions: float
    method: str  # 'dft' or 'least_squares'

class CentrifugeRun:
    accel_g: float
    omega_rad_s: Optional[float]
    beta_rad: float
    amplitudes: list[float]  # k0, k1c, k1s, k2c, k2s (deg/h)
    harmonic_fit: Optional[HarmonicFit]
    location: str
    def __init__(
        self, accel_g: float, beta_rad: float, amplitudes: Sequence[float], omega_rad_s: Optional[float] = None
    ) -> None: ...
    @staticmethod
    def from_samples(
        accel_g: float, beta_rad: float, gamma_rad: ArrayLike, output: ArrayLike, omega_rad_s: Optional[float] = None
    ) -> CentrifugeRun: ...

class CentrifugeRecord:
    kind: str  # 'harmonics' or 'samples'
    def runs(self) -> list[CentrifugeRun]: ...

def read_centrifuge_record(path: str) -> CentrifugeRecord: ...
def analyse_harmonics(gamma_rad: ArrayLike, output: ArrayLike) -> HarmonicFit:
    """Eq. (11) of the centrifuge paper: k0 + k1c cos g + k1s sin g + k2c cos 2g + k2s sin 2g."""

class DriftCalibrationResult(Result):
    coefficients: Record  # D_F ... D_OS, Figures with 1-sigma uncertainties
    residual_rms: Figure
    degrees_of_freedom: int
    g_levels: int
    centrifuge_errors: Record
    influence: list[Record]
    runs: list[Record]
    warnings: list[str]

def calibrate_drift_coefficients(
    runs: Sequence[CentrifugeRun],
    *,
    latitude_deg: Optional[float] = None,
    radius_m: float = 1.0,
    gravity_m_s2: float = 9.80665,
    k1_rad: Optional[float] = None,
    k2_rad: Optional[float] = None,
    delta_omega_rad_s: Optional[float] = None,
    compensation: bool = True,
    estimate_errors: bool = False,
    rank_threshold: float = 1e-4,
) -> DriftCalibrationResult:
    """q = (Phi^T Phi)^-1 Phi^T (Y - epsilon), the centrifuge paper's eqs. (12)-(16), error influence (section 6)."""

def centrifuge_model_output(
    coefficients: Sequence[float],
    omega_rad_s: float,
    beta_rad: float,
    gamma_rad: ArrayLike,
    *,
    radius_m: float = 1.0,
    latitude_deg: float = 0.0,
    gravity_m_s2: float = 9.80665,
    k1_rad: float = 0.0,
    k2_rad: float = 0.0,
    delta_omega_rad_s: float = 0.0,
) -> FloatArray:
    """First-order model output (deg/h): eq. (2) with the inputs of eqs. (5)-(8) of the centrifuge paper."""

# sim -------------------------------------------------------------------------------------------

def gyro_noise(
    sample_count: int,
    sample_rate_hz: float,
    *,
    quantization: float = 0.0,
    angle_random_walk: float = 0.0,
    bias_instability: float = 0.0,
    rate_random_walk: float = 0.0,
    rate_ramp: float = 0.0,
    flicker_shortest_s: float = 1.0,
    flicker_longest_s: float = 1.0e5,
    seed: int = 1,
) -> FloatArray:
    """Gyro random drift (rad/s) with the Allan deviations of IEEE Std 952-1997 C.1 (SI units)."""

def simulate(plan_path: str, out_dir: str) -> Record:
    """Runs a simulation plan as `inertest simulate`; Record with truth, plan_path, written_files."""

# campaign --------------------------------------------------------------------------------------

class CampaignResult(Result): ...

def plan_kinds() -> list[str]:
    """Every procedure kind a test plan may name, sorted."""
def validate_plan(plan_path: str) -> dict[str, Any]: ...
def run_campaign(plan_path: str, out_dir: str) -> CampaignResult:
    """Runs a test plan as `inertest run` and writes out_dir/results.json."""

# specs: every declared procedure ----------------------------------------------------------------

class ProcedureResult(Result):
    """The result of a declared procedure: members as in the CLI's --json object."""

def procedure_specs() -> list[dict[str, Any]]:
    """Every declared procedure: kind, title, clause, parameters, inputs, fields, generic_function."""
