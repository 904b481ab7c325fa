"""Writes tumble.csv, the worked example of `inertest imu-calibration`: a synthetic IMU (the model of
include/inertest/procedures/imu_calibration.h, in counts with offsets near 32768) held still by hand
for 10 s, then turned 11 times by 60 to 150 degrees about random axes over 2 to 3 s (a cycloidal
profile: the rate and its acceleration rise from zero and fall to zero), each followed by 5 s held
still; 25 Hz, white noise of 3 counts (accelerometer) and 4 counts (gyro), rounded to whole
counts, local gravity 9.80665 m/s^2. Run: python3 make_tumble.py (numpy)."""
import numpy as np

RATE = 25.0
GRAVITY = 9.80665
ACCELEROMETER = dict(bias=[33120.0, 33275.0, 32364.0], scale=[414.4, 412.0, 414.6],
                     misalignment=[[0, 0.0034, -0.0096], [0, 0, 0.0214], [0, 0, 0]])
GYRO = dict(bias=[32777.0, 32459.0, 32512.0], scale=[6258.0, 6190.0, 6320.0],
            misalignment=[[0, 0.012, -0.004], [-0.007, 0, 0.009], [0.015, -0.011, 0]])


def output(triad, inputs):
    """output = diag(scale) (I + M)^-1 input + bias, the model inverted."""
    inverse = np.linalg.inv(np.eye(3) + np.array(triad["misalignment"]))
    return (np.array(triad["scale"])[:, None] * (inverse @ inputs.T)).T + np.array(triad["bias"])


def rotation(axis, angle):
    x, y, z = axis
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def main():
    random = np.random.default_rng(18)
    attitude = np.eye(3)
    forces, rates = [], []

    def hold(seconds):
        for _ in range(int(seconds * RATE)):
            forces.append(attitude[2] * GRAVITY)
            rates.append(np.zeros(3))

    hold(10.0)
    for _ in range(11):
        axis = random.normal(size=3)
        axis /= np.linalg.norm(axis)
        angle = np.radians(60.0 + 90.0 * random.uniform())
        samples = int((2.0 + random.uniform()) * RATE)
        duration = samples / RATE
        start = attitude
        for i in range(1, samples + 1):  # the cycloidal profile: speed and acceleration 0 at both ends
            s = i / samples
            attitude = start @ rotation(axis, angle * (s - np.sin(2 * np.pi * s) / (2 * np.pi)))
            forces.append(attitude[2] * GRAVITY)
            rates.append(axis * angle / duration * (1 - np.cos(2 * np.pi * s)))
        hold(5.0)
    accelerometer = np.round(output(ACCELEROMETER, np.array(forces)) + 3.0 * random.normal(size=(len(forces), 3)))
    gyro = np.round(output(GYRO, np.array(rates)) + 4.0 * random.normal(size=(len(rates), 3)))
    with open("tumble.csv", "w") as f:
        f.write("time_s,ax,ay,az,gx,gy,gz\n")
        for i, (a, w) in enumerate(zip(accelerometer, gyro)):
            f.write("%.2f,%d,%d,%d,%d,%d,%d\n" % (i / RATE, *a, *w))


if __name__ == "__main__":
    main()
