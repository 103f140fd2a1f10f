"""Reference topocentric airless sun directions for tests/sun.rs.

Generated with astropy 8.0.1 (its builtin ephemeris: ERFA's epv00 for the Earth,
IAU 2006/2000A precession-nutation), offline:

    python3 -m venv /tmp/astrovenv && /tmp/astrovenv/bin/pip install astropy==8.0.1
    /tmp/astrovenv/bin/python crates/celestial/tests/data/sun_reference.py \
        > crates/celestial/tests/data/sun_reference.csv

Columns: UTC instant (RFC 3339), latitude (deg), longitude (deg, east), elevation (m),
azimuth (deg from north through east), elevation angle (deg), distance (km,
topocentric). Pressure 0: no refraction. UT1 is set equal to UTC, as in celestial.
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

rng = np.random.default_rng(1950)
start = Time("1950-01-01T00:00:00", scale="utc").unix
end = Time("2100-12-31T00:00:00", scale="utc").unix
print("instant,latitude_deg,longitude_deg,elevation_m,azimuth_deg,elevation_deg,distance_km")
with solar_system_ephemeris.set("builtin"):
    for k in range(200):
        unix = start + (end - start) * k / 199.0 + rng.uniform(0, 86400)
        t = Time(min(unix, end), format="unix", scale="utc")
        # UT1 = UTC, as celestial assumes (and IERS has no UT1 beyond its tables).
        t.delta_ut1_utc = 0.0
        lat = float(rng.uniform(-89.5, 89.5)) if k % 10 else (89.9 if k % 20 else -89.9)
        lon = float(rng.uniform(-180, 180)) if k % 7 else (180.0 if k % 14 else -180.0)
        elev = float(rng.uniform(0, 4000))
        loc = EarthLocation.from_geodetic(lon * u.deg, lat * u.deg, elev * u.m)
        body = get_body("sun", t, loc).transform_to(AltAz(obstime=t, location=loc, pressure=0))
        stamp = t.utc.isot
        print(f"{stamp}Z,{lat:.6f},{lon:.6f},{elev:.1f},{body.az.deg:.6f},{body.alt.deg:.6f},{body.distance.to(u.km).value:.1f}")
