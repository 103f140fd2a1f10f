"""Reference topocentric airless planet directions for tests/planets.rs.

Generated with astropy 8.0.1 (its builtin ephemeris: ERFA's plan94, Simon et al.
1994, with light time; IAU 2006/2000A precession-nutation), offline:

    python3 -m venv /tmp/astrovenv && /tmp/astrovenv/bin/pip install astropy==8.0.1
    /tmp/astrovenv/bin/python crates/celestial/tests/data/planet_reference.py \
        > crates/celestial/tests/data/planet_reference.csv

Columns: planet, UTC instant (RFC 3339), latitude (deg), longitude (deg, east),
elevation (m), azimuth (deg from north through east), elevation angle (deg). Pressure
0: no refraction. UT1 is set equal to UTC, as in celestial.
"""

import warnings

import numpy as np
from astropy import units as u
from astropy.coordinates import AltAz, EarthLocation, get_body, solar_system_ephemeris
from astropy.time import Time
from astropy.utils import iers

iers.conf.auto_download = False
iers.conf.iers_degraded_accuracy = "ignore"
warnings.simplefilter("ignore")

rng = np.random.default_rng(415)
start = Time("1950-01-01T00:00:00", scale="utc").unix
end = Time("2100-12-31T00:00:00", scale="utc").unix
print("planet,instant,latitude_deg,longitude_deg,elevation_m,azimuth_deg,elevation_deg")
with solar_system_ephemeris.set("builtin"):
    for planet in ["mercury", "venus", "mars", "jupiter", "saturn", "uranus", "neptune"]:
        for k in range(60):
            unix = start + (end - start) * k / 59.0 + rng.uniform(0, 86400)
            t = Time(min(unix, end), format="unix", scale="utc")
            t.delta_ut1_utc = 0.0
            lat = float(rng.uniform(-89.5, 89.5))
            lon = float(rng.uniform(-180, 180))
            loc = EarthLocation.from_geodetic(lon * u.deg, lat * u.deg, 0 * u.m)
            body = get_body(planet, t, loc).transform_to(AltAz(obstime=t, location=loc, pressure=0))
            print(f"{planet},{t.utc.isot}Z,{lat:.6f},{lon:.6f},0.0,{body.az.deg:.6f},{body.alt.deg:.6f}")
