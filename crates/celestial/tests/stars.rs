//! Star apparent places against two independent sources (`tests/data/star_reference.py`
//! → `.csv`): astropy 8.0.1 (ERFA, IAU 2006/2000A; the Hipparcos new reduction's
//! places, proper motions and parallaxes read from hip2.dat itself) for the
//! geocentric apparent α, δ at 17 instants 1900–2100 and the topocentric airless
//! direction 1950–2100, and PyEphem 4.2.1 (its own star list and reduction, ~1″) for
//! the airless direction of the stars it knows. 18 stars: the brightest, both
//! pole stars, and the fastest-moving of the catalogue (α Centauri A, Arcturus,
//! Groombridge 1830, 61 Cygni A, Lacaille 9352, ε Indi, Lalande 21185).
//!
//! Goal: 0.003° (10.8″) everywhere. The two sources are checked against each other
//! too (within 2″, PyEphem's stated ~1″ twice over).

use std::collections::BTreeMap;

use celestial::astrometry::ApparentFrame;
use celestial::{Angle, Instant, Observer, StarCatalogue};

const GOAL_DEG: f64 = 0.003;

/// Great-circle angle between two directions given as (longitude, latitude) in
/// degrees (right ascension and declination, or azimuth and elevation).
fn separation_deg(lon1: f64, lat1: f64, lon2: f64, lat2: f64) -> f64 {
    let (lon1, lat1, lon2, lat2) = (
        lon1.to_radians(),
        lat1.to_radians(),
        lon2.to_radians(),
        lat2.to_radians(),
    );
    let h = ((lat2 - lat1) / 2.0).sin().powi(2)
        + lat1.cos() * lat2.cos() * ((lon2 - lon1) / 2.0).sin().powi(2);
    (2.0 * h.sqrt().min(1.0).asin()).to_degrees()
}

struct Row<'a> {
    hip: usize,
    julian_day_tt: f64,
    ra_deg: f64,
    dec_deg: f64,
    topocentric: Option<Topocentric<'a>>,
}

struct Topocentric<'a> {
    utc: &'a str,
    latitude_deg: f64,
    longitude_deg: f64,
    azimuth_deg: f64,
    elevation_deg: f64,
    ephem: Option<(f64, f64)>,
}

fn reference() -> Vec<Row<'static>> {
    let table = include_str!("data/star_reference.csv");
    table
        .lines()
        .filter(|line| !line.starts_with('#'))
        .skip(1)
        .map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            assert_eq!(f.len(), 11, "{line}");
            let num = |i: usize| f[i].parse::<f64>().unwrap();
            let topocentric = (!f[4].is_empty()).then(|| Topocentric {
                utc: f[4],
                latitude_deg: num(5),
                longitude_deg: num(6),
                azimuth_deg: num(7),
                elevation_deg: num(8),
                ephem: (!f[9].is_empty()).then(|| (num(9), num(10))),
            });
            Row {
                hip: f[0].parse().unwrap(),
                julian_day_tt: num(1),
                ra_deg: num(2),
                dec_deg: num(3),
                topocentric,
            }
        })
        .collect()
}

/// The worst separation per star (name or number) and overall, printed.
fn report(what: &str, worst: &BTreeMap<usize, f64>) -> f64 {
    let catalogue = StarCatalogue::hipparcos(8.0).unwrap();
    let mut line = String::new();
    for (hip, sep) in worst {
        let star = catalogue.find(&hip.to_string()).unwrap();
        let name = star
            .name
            .map_or_else(|| format!("HIP {hip}"), str::to_owned);
        line += &format!(" {name} {:.5}°;", sep);
    }
    let max = worst.values().copied().fold(0.0, f64::max);
    println!("{what}: max {max:.5}° —{line}");
    max
}

/// The worst separation per star of the geocentric apparent places, with the
/// catalogue's proper motions or without them (to show that the check can fail).
fn geocentric_worst(motion: bool) -> (BTreeMap<usize, f64>, usize) {
    let catalogue = StarCatalogue::hipparcos(8.0).unwrap();
    let mut worst = BTreeMap::new();
    let mut count = 0;
    for row in reference() {
        let frame = ApparentFrame::at_julian_day_tt(row.julian_day_tt).unwrap();
        let mut star = *catalogue.find(&format!("HIP {}", row.hip)).unwrap();
        if !motion {
            star.proper_motion_ra_cos_dec = Angle::ZERO;
            star.proper_motion_dec = Angle::ZERO;
        }
        let (ra, dec) = frame.apparent_place(&star.astrometry());
        let sep = separation_deg(ra.degrees(), dec.degrees(), row.ra_deg, row.dec_deg);
        let entry = worst.entry(row.hip).or_insert(0.0_f64);
        *entry = entry.max(sep);
        count += 1;
    }
    (worst, count)
}

#[test]
fn geocentric_apparent_places_within_0_003_degrees_1900_2100() {
    let (worst, count) = geocentric_worst(true);
    assert_eq!(count, 18 * 17);
    let max = report("apparent α, δ vs astropy, 1900–2100", &worst);
    assert!(max < GOAL_DEG, "{max}");
}

/// The same comparison without proper motion fails: the check can fail.
#[test]
fn without_proper_motion_the_places_fail_the_goal() {
    let (worst, _) = geocentric_worst(false);
    let max = report("apparent α, δ vs astropy without proper motion", &worst);
    assert!(max > 10.0 * GOAL_DEG, "{max}");
}

#[test]
fn airless_directions_within_0_003_degrees_1950_2100() {
    let catalogue = StarCatalogue::hipparcos(8.0).unwrap();
    let mut worst_astropy = BTreeMap::new();
    let mut worst_ephem = BTreeMap::new();
    let (mut count, mut ephem_count) = (0, 0);
    let mut sources_apart = 0.0_f64;
    for row in reference() {
        let Some(topo) = row.topocentric else {
            continue;
        };
        let instant = Instant::parse(topo.utc).unwrap();
        let observer = Observer::new(
            Angle::from_degrees(topo.latitude_deg),
            Angle::from_degrees(topo.longitude_deg),
            0.0,
        )
        .unwrap();
        let star = catalogue
            .sky(&instant, &observer)
            .into_iter()
            .find(|s| s.hip == row.hip)
            .unwrap();
        let (az, el) = (
            star.airless.azimuth.degrees(),
            star.airless.elevation.degrees(),
        );
        let sep = separation_deg(az, el, topo.azimuth_deg, topo.elevation_deg);
        let entry = worst_astropy.entry(row.hip).or_insert(0.0_f64);
        *entry = entry.max(sep);
        count += 1;
        if let Some((ephem_az, ephem_el)) = topo.ephem {
            sources_apart = sources_apart.max(separation_deg(
                topo.azimuth_deg,
                topo.elevation_deg,
                ephem_az,
                ephem_el,
            ));
            let sep = separation_deg(az, el, ephem_az, ephem_el);
            let entry = worst_ephem.entry(row.hip).or_insert(0.0_f64);
            *entry = entry.max(sep);
            ephem_count += 1;
        }
    }
    assert_eq!(count, 18 * 13);
    assert_eq!(ephem_count, 12 * 13);
    let max = report("airless az, el vs astropy, 1950–2100", &worst_astropy);
    let max_ephem = report("airless az, el vs PyEphem, 1950–2100", &worst_ephem);
    println!("astropy vs PyEphem: max {:.2}″", sources_apart * 3600.0);
    assert!(sources_apart * 3600.0 < 2.0, "{sources_apart}");
    assert!(max < GOAL_DEG, "{max}");
    assert!(max_ephem < GOAL_DEG, "{max_ephem}");
}
