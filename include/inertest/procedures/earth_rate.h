// The component of Earth rate along an instrument axis at a site: the input the Earth feeds to a
// gyro at rest. Used where GJB 2426A-2004 removes or uses Earth rate (5.5.4, 5.10.4.2-5.10.4.3,
// and the optional Earth-rate removal of the bias, 5.12.1).
#pragma once

namespace inertest {

// Orientation of the input reference axis (IRA) at the site.
struct AxisOrientation {
  double latitude_deg = 0.0;   // geodetic latitude of the site, north positive
  double heading_deg = 0.0;    // azimuth of the IRA's horizontal projection from north, east positive
  double elevation_deg = 0.0;  // angle of the IRA above the horizontal plane, up positive

  // Throws Error when the latitude or elevation lies outside [-90, 90] or a value is not finite; a
  // latitude left NaN (not given) is a ParameterError on latitude_deg: the Earth rate depends on it.
  void validate() const;
};

// Earth rate along the IRA in rad/s. The Earth-rate vector has the components Ωe·cos φ north and
// Ωe·sin φ up (φ latitude); the IRA's unit vector is (cos e·cos h north, cos e·sin h east, sin e up),
// so the component is Ωe·(cos φ·cos e·cos h + sin φ·sin e). With e = 0 this is eq. (16)/(17) of
// GJB 2426A-2004: Ωe·cos φ·cos β.
double earth_rate_on_axis(const AxisOrientation& axis);

}  // namespace inertest
