//! [`Inspector`]: a window with every component's probe images and named states, live.

use std::time::{Duration, Instant};

use yarok_core::BoxError;
use yarok_core::component::ProbeImage;
use yarok_core::runtime::{Plugin, World};
use yarok_mjc::{Gallery, Picture, TextRow, WindowEvent};

/// How the [`Inspector`] shows probes (`[plugins.inspector]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct InspectorSettings {
    /// How many times a wall-clock second the probes are read and shown.
    pub rate: f64,
    /// The widest the window grows before images wrap to a new row (pixels).
    pub max_width: u32,
}

impl Default for InspectorSettings {
    fn default() -> Self {
        Self {
            rate: 5.0,
            max_width: 1300,
        }
    }
}

/// Shows every component's probes — camera colour and depth, tactile images — side by side in
/// a window, each under its component's path, and under them every component's named states
/// (one row per field: `/arm state q` and its values, numbers to three decimals), refreshed
/// `rate` times a wall-clock second (the Python original's CV2Inspector, which showed images
/// only). Depth shows grey, nearer brighter. Closing the window ends the run. Works in every
/// environment.
///
/// Registered by `yarok::platform()` (feature `viewer`) as `inspector`; `yarok run WORLD
/// --inspect` adds it.
#[derive(Debug)]
pub struct Inspector {
    settings: InspectorSettings,
    gallery: Option<Gallery>,
    last: Option<Instant>,
    labels: Vec<String>,
    images: Vec<(u32, u32, Vec<u8>)>,
    rows: Vec<(String, String)>,
}

impl Inspector {
    /// An inspector with these settings; the window opens when the run starts.
    ///
    /// # Errors
    ///
    /// When `rate` is not a positive number.
    pub fn new(settings: InspectorSettings) -> Result<Self, BoxError> {
        if !(settings.rate > 0.0 && settings.rate.is_finite()) {
            return Err(format!("`rate` {} must be above 0", settings.rate).into());
        }
        Ok(Self {
            settings,
            gallery: None,
            last: None,
            labels: Vec::new(),
            images: Vec::new(),
            rows: Vec::new(),
        })
    }
}

/// `image` as RGB pixels: depth grey, from white at its nearest to black at its farthest.
fn rgb(image: ProbeImage) -> Result<(u32, u32, Vec<u8>), BoxError> {
    match image {
        ProbeImage::Rgb {
            width,
            height,
            pixels,
        } => Ok((width, height, pixels)),
        ProbeImage::Depth {
            width,
            height,
            metres,
            ..
        } => {
            let finite = metres.iter().copied().filter(|m| m.is_finite());
            let near = finite.clone().fold(f32::INFINITY, f32::min);
            let far = finite.fold(f32::NEG_INFINITY, f32::max);
            let span = (far - near).max(f32::EPSILON);
            let pixels = metres
                .iter()
                .flat_map(|m| [(255.0 * (far - m) / span).clamp(0.0, 255.0) as u8; 3])
                .collect();
            Ok((width, height, pixels))
        }
        _ => Err("a probe image of an unknown kind".into()),
    }
}

/// A named state's table rows: one per field of an object (`/arm state q`), else one.
fn state_rows(name: &str, value: &serde_json::Value, rows: &mut Vec<(String, String)>) {
    match value {
        serde_json::Value::Object(fields) if !fields.is_empty() => {
            for (field, value) in fields {
                rows.push((format!("{name} {field}"), shown(value)));
            }
        }
        _ => rows.push((name.to_owned(), shown(value))),
    }
}

/// `value` as short text: numbers to three decimals, arrays space-separated in brackets.
fn shown(value: &serde_json::Value) -> String {
    let joined = |items: Vec<String>| items.join(" ");
    match value {
        serde_json::Value::Number(number) => match number.as_f64() {
            Some(x) if number.is_f64() => format!("{x:.3}"),
            _ => number.to_string(),
        },
        serde_json::Value::String(text) => text.clone(),
        serde_json::Value::Array(items) => {
            format!("[{}]", joined(items.iter().map(shown).collect()))
        }
        serde_json::Value::Object(fields) => {
            let fields = fields.iter().map(|(k, v)| format!("{k}: {}", shown(v)));
            format!("{{{}}}", joined(fields.collect()))
        }
        other => other.to_string(),
    }
}

impl Plugin for Inspector {
    fn name(&self) -> String {
        "inspector".into()
    }

    fn start(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        self.labels = world
            .probes()
            .iter()
            .map(|probe| format!("{} {}", probe.component(), probe.name()))
            .collect();
        self.gallery = Some(Gallery::open("yarok inspector")?);
        Ok(())
    }

    fn step(&mut self, world: &World<'_>) -> Result<(), BoxError> {
        let Some(gallery) = &mut self.gallery else {
            return Ok(());
        };
        if gallery.events().contains(&WindowEvent::Close) {
            world.pl().stop();
            return Ok(());
        }
        let period = Duration::from_secs_f64(1.0 / self.settings.rate);
        if self.last.is_some_and(|last| last.elapsed() < period) {
            return Ok(());
        }
        self.last = Some(Instant::now());
        self.images.clear();
        for probe in world.probes() {
            let image = probe.read()?;
            self.images.push(rgb(image)?);
        }
        self.rows.clear();
        for state in world.states() {
            let name = format!("{} {}", state.component(), state.name());
            state_rows(&name, &state.read()?, &mut self.rows);
        }
        let table: Vec<TextRow<'_>> = self
            .rows
            .iter()
            .map(|(name, value)| TextRow { name, value })
            .collect();
        let pictures: Vec<Picture<'_>> = self
            .labels
            .iter()
            .zip(&self.images)
            .map(|(label, (width, height, rgb))| Picture {
                label,
                width: *width,
                height: *height,
                rgb,
            })
            .collect();
        gallery.show(&pictures, &table, self.settings.max_width)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::state_rows;

    #[test]
    fn a_state_shows_one_row_per_field_with_numbers_to_three_decimals() {
        let mut rows = Vec::new();
        let arm = json!({"q": [0.0, -1.234_56], "moving": false, "mode": "run", "n": 3});
        state_rows("/arm state", &arm, &mut rows);
        state_rows("/dimmer level", &json!(0.25), &mut rows);
        // Fields in name order, as serde_json's map keeps them.
        let expected = [
            ("/arm state mode", "run"),
            ("/arm state moving", "false"),
            ("/arm state n", "3"),
            ("/arm state q", "[0.000 -1.235]"),
            ("/dimmer level", "0.250"),
        ];
        let expected: Vec<_> = expected.map(|(n, v)| (n.to_owned(), v.to_owned())).into();
        assert_eq!(rows, expected);
    }
}
