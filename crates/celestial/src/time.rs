//! A UTC instant within the supported span, with the time scales the ephemerides need.
//!
//! * Parsing: ISO 8601 in its RFC 3339 profile (`2003-10-17T12:30:30-07:00`,
//!   `…Z`, fractional seconds allowed), through `chrono`, a maintained, widely used
//!   parser. A date-time without a UTC offset is rejected: it would be local time
//!   in an unknown zone.
//! * UT1 is taken equal to UTC (|UT1 − UTC| < 0.9 s, i.e. < 0.004° of Earth
//!   rotation); leap seconds are not represented (chrono's convention).
//! * TT = UT + ΔT, with ΔT from the Espenak–Meeus polynomials (2014 update, NASA
//!   eclipse web site) and, from 2015, a fit to IERS observations through 2026
//!   continued by a fit to Agnew's (2026) projections — as implemented by
//!   `solar_positioning::delta_t` (the ΔT model that ships with the SPA used for the
//!   sun). ΔT beyond 2026 is an extrapolation (uncertain by tens of seconds by
//!   2100), which moves the sun along its path by < 0.001°; it can be overridden
//!   with [`Instant::with_delta_t`].

use chrono::{DateTime, Datelike, NaiveDate, Utc};

use crate::error::{CelestialError, Result, check_range};

/// First supported instant (inclusive).
pub const SPAN_START: &str = "1950-01-01T00:00:00Z";
/// First instant after the supported span (exclusive): the span is 1950–2100.
pub const SPAN_END: &str = "2101-01-01T00:00:00Z";

/// Julian day of the Unix epoch 1970-01-01T00:00:00 UTC.
const UNIX_EPOCH_JULIAN_DAY: f64 = 2_440_587.5;
/// Julian day of J2000.0 (2000-01-01T12:00 TT).
pub const J2000_JULIAN_DAY: f64 = 2_451_545.0;
/// Days per Julian century.
pub const DAYS_PER_JULIAN_CENTURY: f64 = 36_525.0;
const SECONDS_PER_DAY: f64 = 86_400.0;
/// |ΔT| accepted by [`Instant::with_delta_t`] (s); the modelled ΔT is 29–~200 s
/// over the span.
const MAX_ABS_DELTA_T_S: f64 = 1_000.0;

/// A UTC instant in 1950–2100 with its ΔT = TT − UT (seconds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instant {
    utc: DateTime<Utc>,
    delta_t_s: f64,
}

impl Instant {
    /// Parses an ISO 8601 / RFC 3339 date-time with an explicit offset (`Z` or `±hh:mm`).
    pub fn parse(text: &str) -> Result<Self> {
        let parsed =
            DateTime::parse_from_rfc3339(text.trim()).map_err(|source| CelestialError::Parse {
                field: "instant",
                input: text.to_owned(),
                source,
            })?;
        Self::from_utc(parsed.with_timezone(&Utc))
    }

    /// The instant `utc`, with the modelled ΔT.
    pub fn from_utc(utc: DateTime<Utc>) -> Result<Self> {
        let start = span_bound(SPAN_START);
        let end = span_bound(SPAN_END);
        if utc < start || utc >= end {
            return Err(CelestialError::OutsideSpan {
                field: "instant",
                value: utc.to_rfc3339(),
                min: SPAN_START,
                max: SPAN_END,
            });
        }
        let delta_t_s = solar_positioning::delta_t::estimate_from_date(utc.year(), utc.month())
            .map_err(|source| CelestialError::Ephemeris {
                field: "delta_t",
                source,
            })?;
        Ok(Instant { utc, delta_t_s })
    }

    /// The UTC calendar instant `year-month-day hour:minute:second` (second may be
    /// fractional, in [0, 60)).
    pub fn from_calendar(
        year: i32,
        month: u32,
        day: u32,
        hour: u32,
        minute: u32,
        second: f64,
    ) -> Result<Self> {
        let second = check_range("second", second, 0.0, 60.0, "s")?;
        let whole = second.floor();
        let nanos = ((second - whole) * 1e9).round().min(999_999_999.0) as u32;
        let utc = NaiveDate::from_ymd_opt(year, month, day)
            .and_then(|date| date.and_hms_nano_opt(hour, minute, whole as u32, nanos))
            .filter(|_| second < 60.0)
            .ok_or_else(|| CelestialError::InvalidCalendar {
                field: "calendar",
                value: format!("{year:04}-{month:02}-{day:02} {hour:02}:{minute:02}:{second}"),
            })?
            .and_utc();
        Self::from_utc(utc)
    }

    /// The same instant with ΔT = `delta_t_s` seconds instead of the model (e.g. a
    /// published example's ΔT, or an IERS value).
    pub fn with_delta_t(self, delta_t_s: f64) -> Result<Self> {
        let delta_t_s = check_range(
            "delta_t",
            delta_t_s,
            -MAX_ABS_DELTA_T_S,
            MAX_ABS_DELTA_T_S,
            "s",
        )?;
        Ok(Instant { delta_t_s, ..self })
    }

    /// The instant as a chrono UTC date-time.
    pub fn utc(&self) -> DateTime<Utc> {
        self.utc
    }

    /// ΔT = TT − UT in seconds.
    pub fn delta_t_seconds(&self) -> f64 {
        self.delta_t_s
    }

    /// Julian day in UT (UT1 ≈ UTC).
    pub fn julian_day_ut(&self) -> f64 {
        let seconds =
            self.utc.timestamp() as f64 + f64::from(self.utc.timestamp_subsec_nanos()) * 1e-9;
        UNIX_EPOCH_JULIAN_DAY + seconds / SECONDS_PER_DAY
    }

    /// Julian ephemeris day (TT).
    pub fn julian_day_tt(&self) -> f64 {
        self.julian_day_ut() + self.delta_t_s / SECONDS_PER_DAY
    }

    /// Julian centuries of UT since J2000.0 (the argument of sidereal time).
    pub fn julian_centuries_ut(&self) -> f64 {
        (self.julian_day_ut() - J2000_JULIAN_DAY) / DAYS_PER_JULIAN_CENTURY
    }

    /// Julian centuries of TT since J2000.0 (the argument of the ephemerides).
    pub fn julian_centuries_tt(&self) -> f64 {
        (self.julian_day_tt() - J2000_JULIAN_DAY) / DAYS_PER_JULIAN_CENTURY
    }
}

fn span_bound(text: &str) -> DateTime<Utc> {
    DateTime::parse_from_rfc3339(text)
        .expect("the span bounds are valid RFC 3339 constants")
        .with_timezone(&Utc)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Meeus, Astronomical Algorithms (2nd ed.), Example 7.a: 1957 Oct 4.81 → JD 2436116.31.
    #[test]
    fn meeus_example_7a_julian_day() {
        // 0.81 d = 19 h 26 m 24 s.
        let instant = Instant::from_calendar(1957, 10, 4, 19, 26, 24.0).unwrap();
        assert!((instant.julian_day_ut() - 2_436_116.31).abs() < 1e-9);
    }

    /// J2000.0 is 2000-01-01T12:00 TT; in UT it is ΔT (≈ 63.8 s) earlier.
    #[test]
    fn j2000() {
        let instant = Instant::parse("2000-01-01T12:00:00Z").unwrap();
        assert_eq!(instant.julian_day_ut(), J2000_JULIAN_DAY);
        let dt = instant.delta_t_seconds();
        assert!((60.0..67.0).contains(&dt), "ΔT(2000) = {dt} s");
        assert!(
            (instant.julian_centuries_tt() * DAYS_PER_JULIAN_CENTURY * 86_400.0 - dt).abs() < 1e-3
        );
    }

    #[test]
    fn parse_offsets_and_fractions() {
        let a = Instant::parse("2003-10-17T12:30:30-07:00").unwrap();
        let b = Instant::parse("2003-10-17T19:30:30Z").unwrap();
        assert_eq!(a, b);
        let c = Instant::parse("2003-10-17T19:30:30.5Z").unwrap();
        assert!(((c.julian_day_ut() - b.julian_day_ut()) * 86_400.0 - 0.5).abs() < 1e-4);
    }

    #[test]
    fn rejects_with_typed_errors() {
        assert!(matches!(
            Instant::parse("2003-10-17T12:30:30"),
            Err(CelestialError::Parse {
                field: "instant",
                ..
            })
        ));
        assert!(matches!(
            Instant::parse("1949-12-31T23:59:59Z"),
            Err(CelestialError::OutsideSpan {
                field: "instant",
                ..
            })
        ));
        assert!(matches!(
            Instant::parse("2101-01-01T00:00:00Z"),
            Err(CelestialError::OutsideSpan { .. })
        ));
        assert!(Instant::parse("2100-12-31T23:59:59.999Z").is_ok());
        assert!(Instant::parse("1950-01-01T00:00:00Z").is_ok());
        assert!(matches!(
            Instant::from_calendar(2001, 4, 31, 0, 0, 0.0),
            Err(CelestialError::InvalidCalendar { .. })
        ));
        assert!(matches!(
            Instant::from_calendar(2001, 4, 1, 0, 0, f64::NAN),
            Err(CelestialError::NotFinite {
                field: "second",
                ..
            })
        ));
        let ok = Instant::parse("2000-01-01T00:00:00Z").unwrap();
        assert!(matches!(
            ok.with_delta_t(f64::INFINITY),
            Err(CelestialError::NotFinite {
                field: "delta_t",
                ..
            })
        ));
        let message = Instant::parse("2200-01-01T00:00:00Z")
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("instant") && message.contains("2200"),
            "{message}"
        );
    }
}
