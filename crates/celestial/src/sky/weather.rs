//! The weather: cloud layers, visibility and fog.

use super::*;
use crate::clouds::{CloudLayer, no_layer};
use crate::error::{Result, check_range};
use crate::visibility::{
    KOSCHMIEDER_CONTRAST, VisibilityAerosol, aerosol_for_visibility, check_visibility,
    exp2_fog_factor, koschmieder_fog_factor,
};

/// Slot length of the "puffy" variation (s): SGSky's ramp.
const PUFF_SLOT_S: f64 = 0.15;
/// Longest puff (s), SGSky's.
const PUFF_MAX_S: f64 = 2.0;

/// The puff envelope in [0, 1] at time `t` for a layer seeded `seed`: SGSky's disabled
/// effect, made frame-rate independent. Each 0.15 s slot starts a puff when a hashed
/// uniform u satisfies u³ > 0.95 (SGSky's test, there per frame), lasting up to 2 s
/// with 0.15 s ramps; overlapping puffs take the largest envelope.
pub fn puff_envelope(seed: u32, t: f64) -> f64 {
    use skyscape_wgsl::common::{hash_combine, unit_float_from_bits};
    let last = (t / PUFF_SLOT_S).floor() as i64;
    let first = ((t - PUFF_MAX_S) / PUFF_SLOT_S).floor() as i64;
    let mut envelope = 0.0f64;
    for slot in first..=last {
        let h = hash_combine(hash_combine(seed, slot as u32), (slot >> 32) as u32);
        let u = f64::from(unit_float_from_bits(h));
        if u * u * u <= 0.95 {
            continue;
        }
        let duration = PUFF_MAX_S * f64::from(unit_float_from_bits(hash_combine(h, 1)));
        let local = t - slot as f64 * PUFF_SLOT_S;
        if local < 0.0 || local > duration {
            continue;
        }
        let ramp = (local / PUFF_SLOT_S)
            .min((duration - local) / PUFF_SLOT_S)
            .clamp(0.0, 1.0);
        envelope = envelope.max(ramp);
    }
    envelope
}

impl Sky {
    /// SGSky's `add_cloud_layer`: checks and appends `layer`; returns its index.
    pub fn add_cloud_layer(&mut self, layer: CloudLayer) -> Result<usize> {
        layer.validate()?;
        self.layers.push(layer);
        self.layers_changed = true;
        Ok(self.layers.len() - 1)
    }

    /// Replaces layer `index`.
    pub fn change_cloud_layer(&mut self, index: usize, layer: CloudLayer) -> Result<()> {
        layer.validate()?;
        let count = self.layers.len();
        let slot = self
            .layers
            .get_mut(index)
            .ok_or_else(|| no_layer(index, count))?;
        *slot = layer;
        self.layers_changed = true;
        Ok(())
    }

    /// Removes and returns layer `index` (later ones move down by one).
    pub fn remove_cloud_layer(&mut self, index: usize) -> Result<CloudLayer> {
        if index >= self.layers.len() {
            return Err(no_layer(index, self.layers.len()));
        }
        self.layers_changed = true;
        Ok(self.layers.remove(index))
    }

    /// SGSky's `get_num_layers`.
    pub fn num_layers(&self) -> usize {
        self.layers.len()
    }

    /// SGSky's `get_cloud_layer(i)`.
    pub fn cloud_layer(&self, index: usize) -> Option<&CloudLayer> {
        self.layers.get(index)
    }

    /// SGSky's `set_visibility` (m, in [1 m, 1000 km]; SGSky clamps below 25 m, this
    /// rejects what is not a visibility). The effective visibility is reset to it.
    pub fn set_visibility(&mut self, visibility_m: f64) -> Result<()> {
        let v = check_visibility("visibility_m", visibility_m)?;
        self.visibility_m = v;
        self.effective_visibility_m = v;
        Ok(())
    }

    /// SGSky's `modify_vis(alt, time_factor)`: advances the sky's clock by `dt_s` and
    /// closes the visibility in around a viewer at `altitude_m` inside or near cloud
    /// layers. Extinctions add: the clear air's 3.912/V plus, per layer, its immersion
    /// (smooth across the transition zones, raised toward 1 by the deterministic
    /// "puffy" envelope while in a transition zone) × coverage × 3.912/in-cloud
    /// visibility. Returns the effective visibility ([`Sky::visibility`]).
    pub fn modify_vis(&mut self, altitude_m: f64, dt_s: f64) -> Result<f64> {
        check_range("altitude_m", altitude_m, -500.0, 1.0e6, "m")?;
        check_range("dt_s", dt_s, 0.0, 1.0e6, "s")?;
        self.clock_s += dt_s;
        let k = -KOSCHMIEDER_CONTRAST.ln();
        let mut extinction = k / self.visibility_m;
        for layer in &self.layers {
            let mut immersion = layer.immersion(altitude_m);
            if immersion > 0.0 && immersion < 1.0 {
                immersion += (1.0 - immersion) * puff_envelope(layer.seed, self.clock_s);
            }
            extinction += immersion * layer.coverage * k / layer.in_cloud_visibility_m;
        }
        self.effective_visibility_m = k / extinction;
        Ok(self.effective_visibility_m)
    }

    /// SGSky's `get_visibility`: the visibility as modified by [`Sky::modify_vis`] (m).
    pub fn visibility(&self) -> f64 {
        self.effective_visibility_m
    }

    /// The sky's clock (s): the sum of `modify_vis`'s `dt`.
    pub fn clock_s(&self) -> f64 {
        self.clock_s
    }

    /// The fog's extinction coefficient (1/m) at the effective visibility.
    pub fn fog_extinction(&self) -> f64 {
        -KOSCHMIEDER_CONTRAST.ln() / self.effective_visibility_m
    }

    /// The fraction of an object's contrast left at `distance_m` by the fog model.
    pub fn fog_factor(&self, distance_m: f64) -> f64 {
        match self.options.fog {
            FogModel::Koschmieder => {
                koschmieder_fog_factor(distance_m, self.effective_visibility_m)
            }
            FogModel::Exp2 => exp2_fog_factor(distance_m, self.effective_visibility_m),
        }
    }

    /// The fog's colour toward horizontal `view` (the dome's horizon colour there).
    pub fn fog_colour(&self, view: [f64; 3]) -> Result<[f64; 3]> {
        let paint = self.painted("fog_colour")?;
        let horizontal = [view[0], view[1], 0.0];
        Ok(paint.dome.radiance(horizontal))
    }

    /// The effective visibility as a physical aerosol for atmos at the viewer's
    /// altitude (Koschmieder).
    pub fn aerosol_atmosphere(&self) -> Result<VisibilityAerosol> {
        aerosol_for_visibility(
            &self.atmosphere,
            self.effective_visibility_m,
            self.altitude_m()?,
        )
    }
}
