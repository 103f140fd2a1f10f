//! `skyscape view --script FILE`: timed actions, one a line, `FRAME ACTION ARGUMENTS`.
//! A frame counts the frames drawn with everything asked before it prepared, so a
//! script draws the same pictures on any machine, however long preparation takes.
//!
//! ```text
//! # comments start with '#'
//! 0 turn 10 -5        # azimuth and elevation, degrees (right and up positive)
//! 0 move 200 0 50     # forward, right and up, metres
//! 1 time 3600         # seconds added to [time] (a [sun] scene: sun ELEVATION AZIMUTH)
//! 1 rung precomputed  # the sky rung (names as --rung)
//! 2 exposure 1.5
//! 2 overlay off
//! 2 temporal off      # march every cloud pixel every frame (on: a quarter a frame)
//! 3 screenshot shot   # shot.png and shot.exr beside each other (never replaced)
//! 4 quit
//! ```

use std::path::PathBuf;

/// One action of a script.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Action {
    /// Turn the view: azimuth and elevation, degrees.
    Turn(f64, f64),
    /// Move: forward, right, up, metres (the camera mode's meaning).
    Move(f64, f64, f64),
    /// Seconds added to `[time]`.
    Time(f64),
    /// `[sun]`'s elevation and azimuth, degrees.
    Sun(f64, f64),
    /// The sky rung, by name.
    Rung(String),
    /// The exposure.
    Exposure(f64),
    /// Show or hide the overlay.
    Overlay(bool),
    /// Amortise the marched clouds over frames, or march every pixel every frame.
    Temporal(bool),
    /// Write the frame as NAME.png and NAME.exr.
    Screenshot(PathBuf),
    /// Close the window.
    Quit,
}

/// A parsed script: actions by frame, in order.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Script {
    pub(crate) actions: Vec<(u32, Action)>,
}

impl Script {
    /// Reads `path`; an error names the file, the line and the value.
    pub(crate) fn open(path: &std::path::Path) -> Result<Self, String> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("--script `{}`: {e}", path.display()))?;
        Self::parse(&text).map_err(|e| format!("--script `{}`: {e}", path.display()))
    }

    /// Parses a script's text.
    pub(crate) fn parse(text: &str) -> Result<Self, String> {
        let mut actions = Vec::new();
        for (number, line) in text.lines().enumerate() {
            let line = line.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let at = |message: String| format!("line {}: {message}", number + 1);
            let words: Vec<&str> = line.split_whitespace().collect();
            let frame: u32 = words[0]
                .parse()
                .map_err(|_| at(format!("frame `{}`: not a frame number", words[0])))?;
            if let Some(&(last, _)) = actions.last()
                && frame < last
            {
                return Err(at(format!(
                    "frame {frame}: comes after frame {last} (actions go in frame order)"
                )));
            }
            let name = words.get(1).copied().unwrap_or("");
            let arguments = &words[words.len().min(2)..];
            let numbers = |count: usize| -> Result<Vec<f64>, String> {
                if arguments.len() != count {
                    return Err(at(format!(
                        "`{name}` takes {count} number{}, got `{}`",
                        if count == 1 { "" } else { "s" },
                        arguments.join(" ")
                    )));
                }
                arguments
                    .iter()
                    .map(|w| {
                        w.parse::<f64>()
                            .ok()
                            .filter(|v| v.is_finite())
                            .ok_or_else(|| at(format!("`{name}` {w}: not a finite number")))
                    })
                    .collect()
            };
            let one_word = || -> Result<&str, String> {
                match arguments {
                    [word] => Ok(*word),
                    _ => Err(at(format!(
                        "`{name}` takes one word, got `{}`",
                        arguments.join(" ")
                    ))),
                }
            };
            let action = match name {
                "turn" => {
                    let v = numbers(2)?;
                    Action::Turn(v[0], v[1])
                }
                "move" => {
                    let v = numbers(3)?;
                    Action::Move(v[0], v[1], v[2])
                }
                "time" => Action::Time(numbers(1)?[0]),
                "sun" => {
                    let v = numbers(2)?;
                    Action::Sun(v[0], v[1])
                }
                "rung" => Action::Rung(one_word()?.to_owned()),
                "exposure" => {
                    let exposure = numbers(1)?[0];
                    if exposure <= 0.0 {
                        return Err(at(format!("`exposure` {exposure}: must be > 0")));
                    }
                    Action::Exposure(exposure)
                }
                "overlay" => match one_word()? {
                    "on" => Action::Overlay(true),
                    "off" => Action::Overlay(false),
                    other => return Err(at(format!("`overlay` {other}: on or off"))),
                },
                "temporal" => match one_word()? {
                    "on" => Action::Temporal(true),
                    "off" => Action::Temporal(false),
                    other => return Err(at(format!("`temporal` {other}: on or off"))),
                },
                "screenshot" => Action::Screenshot(PathBuf::from(one_word()?)),
                "quit" => {
                    if !arguments.is_empty() {
                        return Err(at(format!(
                            "`quit` takes nothing, got `{}`",
                            arguments.join(" ")
                        )));
                    }
                    Action::Quit
                }
                "" => return Err(at(format!("frame {frame}: no action"))),
                other => {
                    return Err(at(format!(
                        "`{other}`: not an action (turn, move, time, sun, rung, exposure, \
                         overlay, temporal, screenshot, quit)"
                    )));
                }
            };
            actions.push((frame, action));
        }
        Ok(Self { actions })
    }

    /// The actions of `frame`, removed from the script.
    pub(crate) fn take(&mut self, frame: u32) -> Vec<Action> {
        let count = self.actions.iter().take_while(|(f, _)| *f <= frame).count();
        self.actions.drain(..count).map(|(_, a)| a).collect()
    }

    /// Whether every action has been taken.
    pub(crate) fn is_done(&self) -> bool {
        self.actions.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_script_reads_in_frame_order() {
        let mut script = Script::parse(
            "# a path\n0 turn 10 -5\n0 move 200 0 50 # up\n\n2 screenshot shot\n3 quit\n",
        )
        .unwrap();
        assert_eq!(
            script.take(0),
            vec![Action::Turn(10.0, -5.0), Action::Move(200.0, 0.0, 50.0)]
        );
        assert!(script.take(1).is_empty());
        assert_eq!(script.take(2), vec![Action::Screenshot("shot".into())]);
        assert!(!script.is_done());
        assert_eq!(script.take(3), vec![Action::Quit]);
        assert!(script.is_done());
    }

    #[test]
    fn errors_name_the_line_and_the_value() {
        let cases = [
            ("0 turn 10\n", "line 1: `turn` takes 2 numbers, got `10`"),
            ("x quit\n", "line 1: frame `x`: not a frame number"),
            ("0 fly 1\n", "line 1: `fly`: not an action"),
            ("1 quit\n0 quit\n", "line 2: frame 0: comes after frame 1"),
            ("0 exposure -1\n", "line 1: `exposure` -1: must be > 0"),
            (
                "0 move 1 NaN 2\n",
                "line 1: `move` NaN: not a finite number",
            ),
            ("0 overlay maybe\n", "line 1: `overlay` maybe: on or off"),
        ];
        for (text, expected) in cases {
            let error = Script::parse(text).unwrap_err();
            assert!(error.starts_with(expected), "{text:?}: {error}");
        }
    }
}
