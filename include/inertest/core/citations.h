// The papers the procedures implement, cited as a user can find them: title, authors and
// institution as printed in the papers, never a file name. One constant per source, used by the CLI
// help, the text reports, the JSON "source" keys and the Python module (inertest.CITATIONS).
#pragma once

namespace inertest::citations {

// The misalignment paper: gyro on a single-axis rate table, accelerometer in a multi-position
// gravity test (implemented in misalignment/).
inline constexpr const char* kMisalignmentPaper =
    "李巍, 任顺清, 赵洪波 (Li Wei, Ren Shunqing, Zhao Hongbo), 《惯性元件的失准角分离技术研究》 "
    "(misalignment angle separation of inertial instruments), Space Control and Inertial Technology Research "
    "Center, Harbin Institute of Technology";

// The centrifuge paper (implemented in centrifuge/). The copy at hand lost its title and authors, so
// it is cited by what it is, with its equation and table numbers.
inline constexpr const char* kCentrifugePaper =
    "the paper on drift-coefficient calibration of a gyro on a precision centrifuge with a counter-rotating "
    "platform";

// The IMU triad calibration without external equipment (implemented in procedures/imu_calibration).
inline constexpr const char* kImuCalibrationPaper =
    "D. Tedaldi, A. Pretto, E. Menegatti, \"A robust and easy to implement method for IMU calibration without "
    "external equipments\", IEEE International Conference on Robotics and Automation (ICRA), 2014";

}  // namespace inertest::citations
