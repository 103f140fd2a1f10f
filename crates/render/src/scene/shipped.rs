//! The scenes shipped with skyscape (`scenes/*.toml`, embedded in the crate so the
//! binary renders them by name from anywhere): `skyscape scenes` lists them,
//! `skyscape render NAME` renders one.

/// A shipped scene: its name, what it shows, and its TOML.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShippedScene {
    /// The name `skyscape render` takes.
    pub name: &'static str,
    /// One line on what it shows.
    pub description: &'static str,
    /// The scene file.
    pub source: &'static str,
}

/// Every shipped scene, the default first.
pub const SHIPPED: &[ShippedScene] = &[
    ShippedScene {
        name: "default",
        description: "an autumn afternoon over procedural mountains with fair-weather cumulus",
        source: include_str!("../../scenes/default.toml"),
    },
    ShippedScene {
        name: "sunset",
        description: "the sun 2° above the horizon: long terrain shadows, a red sun",
        source: include_str!("../../scenes/sunset.toml"),
    },
    ShippedScene {
        name: "above_clouds",
        description: "flying at 4,200 m over a stratus deck with the peaks standing out of it, cirrus above",
        source: include_str!("../../scenes/above_clouds.toml"),
    },
    ShippedScene {
        name: "night",
        description: "a full-moon winter night in the Alps: moon, Jupiter and stars over dark ridges",
        source: include_str!("../../scenes/night.toml"),
    },
    ShippedScene {
        name: "cumulus",
        description: "a cumulus grown by cloudsim and ray-marched by cloudlight over hills, its foot behind them",
        source: include_str!("../../scenes/cumulus.toml"),
    },
    ShippedScene {
        name: "billboards",
        description: "a cumulus field grown by cloudsim, lit by slices and drawn as Dobashi et al. 2000's billboards over hills",
        source: include_str!("../../scenes/billboards.toml"),
    },
    ShippedScene {
        name: "stratocumulus",
        description: "a deck of stratocumulus over hills seen from a valley: Schneider's (GPU Pro 7, 2015) ray-marched cloud shell",
        source: include_str!("../../scenes/stratocumulus.toml"),
    },
    ShippedScene {
        name: "fog",
        description: "3 km visibility under two broken decks drifting on the wind: hills fading into the haze",
        source: include_str!("../../scenes/fog.toml"),
    },
    ShippedScene {
        name: "flight",
        description: "48 frames climbing through a broken stratus deck: in-cloud fog, then above the deck",
        source: include_str!("../../scenes/flight.toml"),
    },
    ShippedScene {
        name: "starfield",
        description: "a moonless January night: Orion, Sirius and the Pleiades to the south-south-east",
        source: include_str!("../../scenes/starfield.toml"),
    },
    ShippedScene {
        name: "orbit",
        description: "the planet's limb from 400 km up, the sun just above it",
        source: include_str!("../../scenes/orbit.toml"),
    },
];

/// The shipped scene called `name`.
pub fn shipped(name: &str) -> Option<&'static ShippedScene> {
    SHIPPED.iter().find(|scene| scene.name == name)
}
