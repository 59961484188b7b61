//! Compiling a [`Composition`] from yarok-core: the MJCF, plus components' keyframes placed in
//! whole-model vectors.

use yarok_core::compose::{ComponentKeyframe, Composition, Instance};
use yarok_core::template::xml::Element;

use crate::error::ModelError;
use crate::model::{Model, to_usize};
use crate::sys;

/// A composition reads its files from disk: no assets in memory.
const NO_ASSETS: [(&str, &[u8]); 0] = [];

impl Model {
    /// Compiles a composed world.
    ///
    /// Components' keyframes address their own joints and actuators; they are placed in
    /// whole-model keyframes (other joints at their initial configuration, other velocities and
    /// controls zero), which takes a second compilation when there are any.
    ///
    /// # Errors
    ///
    /// As [`Model::from_xml_str`], except that a compile error MuJoCo reports against a line of
    /// the composed MJCF names the component, template, line:column and element it came from;
    /// [`ModelError::Keyframe`] when a keyframe has more values than
    /// its component has coordinates, uses mocap vectors, or the world generates joints the
    /// composer cannot count (`composite`, `flexcomp`, `replicate`, `attach`).
    ///
    /// # Examples
    ///
    /// ```
    /// use yarok_core::compose::compose;
    /// use yarok_core::component::{Component, Declaration};
    /// use yarok_mjc::Model;
    ///
    /// struct Pendulum;
    /// impl Component for Pendulum {
    ///     fn declaration() -> Declaration {
    ///         Declaration::new("pendulum").template(r#"<mujoco>
    ///             <worldbody><body name="bob"><joint name="hinge"/><geom size="0.1"/></body></worldbody>
    ///             <keyframe><key name="up" qpos="3.14"/></keyframe>
    ///         </mujoco>"#)
    ///     }
    /// }
    ///
    /// let model = Model::from_composition(&compose::<Pendulum>()?)?;
    /// assert_eq!(model.ffi().nkey, 1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_composition(composition: &Composition) -> Result<Self, ModelError> {
        if let Some((element, problem)) = crate::guard::known_abort(&composition.mjcf) {
            return Err(ModelError::Compile {
                origin: composition
                    .source_of(element)
                    .map_or_else(|| "the composed world".to_owned(), |s| s.to_string()),
                message: problem.to_owned(),
            });
        }
        crate::compile_notice::announcing_long(&composition.mjcf, || {
            Self::compile_composed(composition)
        })
    }

    /// Compiles the composed world, then again with its component keyframes placed.
    fn compile_composed(composition: &Composition) -> Result<Self, ModelError> {
        let model = Self::compile_xml(&composition.to_xml(), NO_ASSETS)
            .map_err(|error| located(error, composition))?;
        if composition.keyframes.is_empty() {
            return Ok(model);
        }
        let first = &composition.keyframes[0];
        let joints: usize = composition.instances.iter().map(|i| i.joints.len()).sum();
        if !composition.layout_known || joints != model.count(crate::ObjectKind::Joint) {
            return Err(keyframe_error(
                first,
                "the world generates joints (composite, flexcomp, replicate or attach), so component keyframes cannot be placed",
            ));
        }
        let mut mjcf = composition.mjcf.clone();
        let mut section = Element::new("keyframe");
        for keyframe in &composition.keyframes {
            section.children.push(model.place(keyframe, composition)?);
        }
        mjcf.children.retain(|s| s.name != "keyframe");
        mjcf.children.push(section);
        Self::compile_xml(&mjcf.to_xml(), NO_ASSETS)
    }

    /// A whole-model `<key>` for a component's keyframe: the keyframes it names in `from`
    /// first, in order, then its own values; everything else at the initial configuration and
    /// zero velocities, controls and activations.
    fn place(
        &self,
        keyframe: &ComponentKeyframe,
        composition: &Composition,
    ) -> Result<Element, ModelError> {
        let mut key = Element::new("key");
        key.set_attribute("name", keyframe.name.clone());
        let mut vectors = Vec::new();
        for (name, value) in &keyframe.attributes {
            match name.as_str() {
                "time" => key.set_attribute("time", value.clone()),
                "from" => {
                    for source in value.split_whitespace() {
                        let source = combined(keyframe, source, composition)?;
                        self.fill(&mut vectors, source, composition)?;
                    }
                }
                _ => {}
            }
        }
        self.fill(&mut vectors, keyframe, composition)?;
        for (name, values) in vectors {
            let text: Vec<String> = values.iter().map(f64::to_string).collect();
            key.set_attribute(name, text.join(" "));
        }
        Ok(key)
    }

    /// Writes `keyframe`'s vectors into the whole-model `vectors`, made on first use.
    fn fill(
        &self,
        vectors: &mut Vec<(&'static str, Vec<f64>)>,
        keyframe: &ComponentKeyframe,
        composition: &Composition,
    ) -> Result<(), ModelError> {
        let instance = composition
            .instance(&keyframe.component)
            .ok_or_else(|| keyframe_error(keyframe, "its component is not in the composition"))?;
        for (name, value) in &keyframe.attributes {
            if matches!(name.as_str(), "time" | "from") {
                continue;
            }
            let local = numbers(value).ok_or_else(|| {
                keyframe_error(keyframe, &format!("`{name}` is not a list of numbers"))
            })?;
            let (vector, initial, slots) = self.slots(name, instance).ok_or_else(|| {
                let message = format!("`{name}` is not supported in component keyframes");
                keyframe_error(keyframe, &message)
            })?;
            if local.len() > slots.len() {
                let message = format!(
                    "`{name}` has {} values but {} has {}",
                    local.len(),
                    instance.path,
                    slots.len()
                );
                return Err(keyframe_error(keyframe, &message));
            }
            let full = match vectors.iter().position(|(n, _)| *n == vector) {
                Some(index) => &mut vectors[index].1,
                None => {
                    vectors.push((vector, initial));
                    &mut vectors.last_mut().expect("just pushed").1
                }
            };
            for (slot, value) in slots.iter().zip(local) {
                full[*slot] = value;
            }
        }
        Ok(())
    }

    /// For the key vector `name`: its attribute name, its initial whole-model value and the
    /// indices of `instance`'s entries in it; `None` for a vector components cannot set.
    fn slots(
        &self,
        name: &str,
        instance: &Instance,
    ) -> Option<(&'static str, Vec<f64>, Vec<usize>)> {
        let m = self.raw();
        let (njnt, nu) = (to_usize(m.njnt), to_usize(m.nu));
        // SAFETY: these model arrays hold the lengths given (nq, njnt, nu entries).
        let (qpos0, jnt_type, qposadr, dofadr, actadr, actnum) = unsafe {
            (
                self.array(m.qpos0, to_usize(m.nq)),
                self.array(m.jnt_type, njnt),
                self.array(m.jnt_qposadr, njnt),
                self.array(m.jnt_dofadr, njnt),
                self.array(m.actuator_actadr, nu),
                self.array(m.actuator_actnum, nu),
            )
        };
        let sizes = |joint: usize| match jnt_type[joint] as u32 {
            sys::mjJNT_FREE => (7, 6),
            sys::mjJNT_BALL => (4, 3),
            _ => (1, 1),
        };
        Some(match name {
            "qpos" => (
                "qpos",
                qpos0.to_vec(),
                expand(&instance.joints, |j| (to_usize(qposadr[j]), sizes(j).0)),
            ),
            "qvel" => (
                "qvel",
                vec![0.0; to_usize(m.nv)],
                expand(&instance.joints, |j| (to_usize(dofadr[j]), sizes(j).1)),
            ),
            "ctrl" => ("ctrl", vec![0.0; nu], instance.actuators.clone()),
            "act" => (
                "act",
                vec![0.0; to_usize(m.na)],
                expand(&instance.actuators, |a| {
                    let count = if actadr[a] < 0 {
                        0
                    } else {
                        to_usize(actnum[a])
                    };
                    (to_usize(actadr[a]), count)
                }),
            ),
            _ => return None,
        })
    }
}

/// The keyframe named `name` that `keyframe`'s `from` combines.
fn combined<'a>(
    keyframe: &ComponentKeyframe,
    name: &str,
    composition: &'a Composition,
) -> Result<&'a ComponentKeyframe, ModelError> {
    let Some(source) = composition.keyframes.iter().find(|k| k.name == name) else {
        let names = composition.keyframes.iter().map(|k| k.name.as_str());
        let message = format!(
            "`from` names keyframe {name:?}, which the world does not have{}",
            yarok_core::suggest::did_you_mean(name, names)
        );
        return Err(keyframe_error(keyframe, &message));
    };
    if source.attributes.iter().any(|(n, _)| n == "from") {
        let message = format!("`from` names {name:?}, which itself combines keyframes");
        return Err(keyframe_error(keyframe, &message));
    }
    Ok(source)
}

/// The model-vector indices of a component's objects, each `(start, count)`.
fn expand(objects: &[usize], span: impl Fn(usize) -> (usize, usize)) -> Vec<usize> {
    objects
        .iter()
        .flat_map(|&object| {
            let (start, count) = span(object);
            start..start + count
        })
        .collect()
}

fn numbers(value: &str) -> Option<Vec<f64>> {
    value.split_whitespace().map(|x| x.parse().ok()).collect()
}

fn keyframe_error(keyframe: &ComponentKeyframe, reason: &str) -> ModelError {
    ModelError::Keyframe {
        component: keyframe.component.clone(),
        name: keyframe.name.clone(),
        reason: reason.to_owned(),
    }
}

/// MuJoCo's error with the composed document's line it names (its last line, `Element …, line
/// N`) replaced by where that element was written.
fn located(error: ModelError, composition: &Composition) -> ModelError {
    let ModelError::Compile { message, .. } = &error else {
        return error;
    };
    let mut lines: Vec<&str> = message.lines().filter(|l| !l.trim().is_empty()).collect();
    let composed_line = lines
        .last()
        .and_then(|last| last.rsplit_once(", line "))
        .and_then(|(_, number)| number.trim().parse::<usize>().ok());
    let Some(source) = composed_line.and_then(|line| composition.source_of_line(line)) else {
        return error;
    };
    lines.pop();
    ModelError::Compile {
        origin: source.to_string(),
        message: lines.join("; "),
    }
}
