//! [`Rtde`]: an async RTDE client (protocol version 2), generic over its transport.

use std::time::Duration;

use tokio::io::{AsyncRead, AsyncWrite, AsyncWriteExt};
use tokio::time::Instant;

use super::message::{ControllerVersion, MessageError, Reply, Request, take_frame};
use super::value::{Recipe, RecipeError, RtdeType, Value};
use crate::reading::{Unread, read_more};

/// The protocol version yarok speaks.
const PROTOCOL: u16 = 2;

/// How the client talks to a controller; every wait is bounded by one of these.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct RtdeSettings {
    /// The controller's name in errors (its address).
    pub name: String,
    /// The longest a reply to a request may take.
    pub reply_timeout: Duration,
    /// The longest the controller may send no data package once outputs are started.
    pub silence: Duration,
}

impl RtdeSettings {
    /// Defaults for the controller called `name`: 2 s for a reply, 100 ms without data.
    pub fn new(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            reply_timeout: Duration::from_secs(2),
            silence: Duration::from_millis(100),
        }
    }
}

/// What went wrong talking RTDE to a controller. Every variant names the controller.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RtdeError {
    /// Reading or writing failed.
    #[error("controller {controller}: RTDE: {source}")]
    Io {
        /// The controller.
        controller: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The connection closed.
    #[error("controller {controller}: RTDE closed while waiting for {waiting_for}")]
    Closed {
        /// The controller.
        controller: String,
        /// What was awaited.
        waiting_for: &'static str,
    },
    /// Nothing came in time.
    #[error("controller {controller}: RTDE: {waiting_for} did not come within {seconds} s")]
    Timeout {
        /// The controller.
        controller: String,
        /// What was awaited.
        waiting_for: &'static str,
        /// The time limit.
        seconds: f64,
    },
    /// A message was malformed.
    #[error("controller {controller}: RTDE: {source}")]
    Message {
        /// The controller.
        controller: String,
        /// What is wrong.
        source: MessageError,
    },
    /// A data package did not match its recipe, or values do not match a recipe.
    #[error("controller {controller}: RTDE: {source}")]
    Recipe {
        /// The controller.
        controller: String,
        /// What is wrong.
        source: RecipeError,
    },
    /// The controller refused a request.
    #[error("controller {controller}: RTDE refused {what}")]
    Refused {
        /// The controller.
        controller: String,
        /// What was asked.
        what: String,
    },
    /// Variables the controller does not know (names are case-sensitive; some need a newer
    /// controller version).
    #[error("controller {controller} (version {version}) has no RTDE variables {names:?}")]
    NotFound {
        /// The controller.
        controller: String,
        /// Its version.
        version: ControllerVersion,
        /// The unknown variables.
        names: Vec<String>,
    },
    /// Input variables another RTDE client already writes.
    #[error("controller {controller}: RTDE inputs {names:?} are in use by another client")]
    InUse {
        /// The controller.
        controller: String,
        /// The variables.
        names: Vec<String>,
    },
}

/// An RTDE client over any byte transport (a TCP stream to port 30004, an in-memory pipe in
/// tests): protocol version 2 negotiated at connect, the controller's version read, an output
/// recipe of named variables at a rate (125 Hz on CB3, up to 500 Hz on e-Series), input
/// recipes, data packages both ways, text messages logged. Every wait is bounded by
/// [`RtdeSettings`].
///
/// ```no_run
/// # async fn run() -> Result<(), Box<dyn std::error::Error>> {
/// use tokio::net::TcpStream;
/// use yarok_hw::ur::rtde::{Rtde, RtdeSettings, Value};
///
/// let stream = TcpStream::connect("192.168.1.10:30004").await?;
/// let mut rtde = Rtde::connect(stream, RtdeSettings::new("192.168.1.10")).await?;
/// let rate = if rtde.controller_version().major >= 5 { 500.0 } else { 125.0 };
/// rtde.setup_outputs(rate, &["timestamp", "actual_q"]).await?;
/// rtde.start().await?;
/// let values = rtde.receive().await?;
/// if let [Value::Double(time), Value::Vector6d(q)] = values[..] {
///     println!("t = {time} s, q = {q:?}");
/// }
/// # Ok(()) }
/// ```
///
/// # Cancel safety
///
/// [`Rtde::receive`] is cancel safe: bytes read stay for the next call, and its silence limit
/// counts from the last data package (or the start), not from the call. The set-up methods are
/// not (a reply may be left unread); call them again after reconnecting.
#[derive(Debug)]
pub struct Rtde<T> {
    stream: T,
    buffer: Vec<u8>,
    settings: RtdeSettings,
    version: ControllerVersion,
    outputs: Option<Recipe>,
    /// When the last data package came (the outputs' start, before the first).
    heard: Instant,
}

impl<T: AsyncRead + AsyncWrite + Unpin> Rtde<T> {
    /// Negotiates protocol version 2 over `transport` and reads the controller's version.
    ///
    /// # Errors
    ///
    /// [`RtdeError`] naming the controller: it refused version 2, did not answer in time, or
    /// the transport failed.
    pub async fn connect(transport: T, settings: RtdeSettings) -> Result<Self, RtdeError> {
        let mut rtde = Self {
            stream: transport,
            buffer: Vec::new(),
            settings,
            version: ControllerVersion {
                major: 0,
                minor: 0,
                bugfix: 0,
                build: 0,
            },
            outputs: None,
            heard: Instant::now(),
        };
        rtde.send_request(&Request::ProtocolVersion(PROTOCOL))
            .await?;
        let accepted = rtde
            .await_reply("the protocol version's acceptance", |reply| match reply {
                Reply::ProtocolVersion { accepted } => Some(accepted),
                _ => None,
            })
            .await?;
        if !accepted {
            return Err(rtde.refused(format!("protocol version {PROTOCOL}")));
        }
        rtde.send_request(&Request::ControllerVersion).await?;
        rtde.version = rtde
            .await_reply("the controller's version", |reply| match reply {
                Reply::ControllerVersion(version) => Some(version),
                _ => None,
            })
            .await?;
        Ok(rtde)
    }

    /// The controller's software version (3.x: CB3; 5.x: e-Series).
    pub fn controller_version(&self) -> ControllerVersion {
        self.version
    }

    /// The settings it was made with.
    pub fn settings(&self) -> &RtdeSettings {
        &self.settings
    }

    /// Asks for the variables `names` at `frequency` Hz; returns the output recipe.
    ///
    /// # Errors
    ///
    /// [`RtdeError::NotFound`] listing the variables the controller does not know; other
    /// [`RtdeError`]s.
    pub async fn setup_outputs(
        &mut self,
        frequency: f64,
        names: &[&str],
    ) -> Result<Recipe, RtdeError> {
        let names: Vec<String> = names.iter().map(|&name| name.to_owned()).collect();
        self.send_request(&Request::SetupOutputs {
            frequency,
            names: names.clone(),
        })
        .await?;
        let (recipe, types) = self
            .await_reply("the output recipe", |reply| match reply {
                Reply::OutputsSetUp { recipe, types } => Some((recipe, types)),
                _ => None,
            })
            .await?;
        let recipe = self.recipe(recipe, names, &types)?;
        self.outputs = Some(recipe.clone());
        Ok(recipe)
    }

    /// Says the variables `names` will come from this client; returns the input recipe to send
    /// them with ([`Rtde::send`]).
    ///
    /// # Errors
    ///
    /// [`RtdeError::InUse`] for variables another client writes, [`RtdeError::NotFound`] for
    /// unknown ones; other [`RtdeError`]s.
    pub async fn setup_inputs(&mut self, names: &[&str]) -> Result<Recipe, RtdeError> {
        let names: Vec<String> = names.iter().map(|&name| name.to_owned()).collect();
        self.send_request(&Request::SetupInputs {
            names: names.clone(),
        })
        .await?;
        let (recipe, types) = self
            .await_reply("the input recipe", |reply| match reply {
                Reply::InputsSetUp { recipe, types } => Some((recipe, types)),
                _ => None,
            })
            .await?;
        let in_use: Vec<String> = names
            .iter()
            .zip(&types)
            .filter(|(_, t)| *t == "IN_USE")
            .map(|(name, _)| name.clone())
            .collect();
        if !in_use.is_empty() {
            return Err(RtdeError::InUse {
                controller: self.settings.name.clone(),
                names: in_use,
            });
        }
        self.recipe(recipe, names, &types)
    }

    /// Starts the outputs.
    ///
    /// # Errors
    ///
    /// [`RtdeError`]; [`RtdeError::Refused`] when the controller refuses (no output recipe).
    pub async fn start(&mut self) -> Result<(), RtdeError> {
        self.send_request(&Request::Start).await?;
        let accepted = self
            .await_reply("the start's acceptance", |reply| match reply {
                Reply::Started { accepted } => Some(accepted),
                _ => None,
            })
            .await?;
        if accepted {
            self.heard = Instant::now();
            Ok(())
        } else {
            Err(self.refused("to start".into()))
        }
    }

    /// Pauses the outputs; data packages already on their way are dropped.
    ///
    /// # Errors
    ///
    /// [`RtdeError`].
    pub async fn pause(&mut self) -> Result<(), RtdeError> {
        self.send_request(&Request::Pause).await?;
        let accepted = self
            .await_reply("the pause's acceptance", |reply| match reply {
                Reply::Paused { accepted } => Some(accepted),
                _ => None,
            })
            .await?;
        if accepted {
            Ok(())
        } else {
            Err(self.refused("to pause".into()))
        }
    }

    /// The values of the next output data package, in the recipe's order, within
    /// [`RtdeSettings::silence`].
    ///
    /// # Errors
    ///
    /// [`RtdeError::Timeout`] when none comes in time; [`RtdeError::Recipe`] when it does not
    /// match the output recipe; other [`RtdeError`]s.
    pub async fn receive(&mut self) -> Result<Vec<Value>, RtdeError> {
        let silence = self.settings.silence;
        let deadline = self.heard + silence;
        loop {
            let reply = self.next_reply("a data package", deadline, silence).await?;
            if let Reply::Data { recipe, payload } = reply
                && let Some(outputs) = &self.outputs
                && outputs.id == recipe
            {
                self.heard = Instant::now();
                return outputs
                    .decode(&payload)
                    .map_err(|source| RtdeError::Recipe {
                        controller: self.settings.name.clone(),
                        source,
                    });
            }
        }
    }

    /// Sends `values` for the input `recipe` (from [`Rtde::setup_inputs`]).
    ///
    /// # Errors
    ///
    /// [`RtdeError::Recipe`] when the values do not match the recipe; [`RtdeError::Io`].
    pub async fn send(&mut self, recipe: &Recipe, values: &[Value]) -> Result<(), RtdeError> {
        let payload = recipe.encode(values).map_err(|source| RtdeError::Recipe {
            controller: self.settings.name.clone(),
            source,
        })?;
        self.send_request(&Request::Data {
            recipe: recipe.id,
            payload,
        })
        .await
    }

    /// The recipe the controller set up for `names`, whose types it sent.
    fn recipe(&self, id: u8, names: Vec<String>, types: &[String]) -> Result<Recipe, RtdeError> {
        let malformed = |reason: String| RtdeError::Message {
            controller: self.settings.name.clone(),
            source: MessageError::Recipe(reason),
        };
        if types.len() != names.len() {
            return Err(malformed(format!(
                "{} types for {} variables",
                types.len(),
                names.len()
            )));
        }
        let missing: Vec<String> = names
            .iter()
            .zip(types)
            .filter(|(_, t)| *t == "NOT_FOUND")
            .map(|(name, _)| name.clone())
            .collect();
        if !missing.is_empty() {
            return Err(RtdeError::NotFound {
                controller: self.settings.name.clone(),
                version: self.version,
                names: missing,
            });
        }
        let variables = names
            .into_iter()
            .zip(types)
            .map(|(name, type_name)| match RtdeType::from_name(type_name) {
                Some(rtde_type) => Ok((name, rtde_type)),
                None => Err(malformed(format!(
                    "`{name}` has an unknown type {type_name}"
                ))),
            })
            .collect::<Result<_, _>>()?;
        Ok(Recipe { id, variables })
    }

    fn refused(&self, what: String) -> RtdeError {
        RtdeError::Refused {
            controller: self.settings.name.clone(),
            what,
        }
    }

    async fn send_request(&mut self, request: &Request) -> Result<(), RtdeError> {
        let bytes = request.encode().map_err(|source| RtdeError::Message {
            controller: self.settings.name.clone(),
            source,
        })?;
        let written = async {
            self.stream.write_all(&bytes).await?;
            self.stream.flush().await
        };
        written.await.map_err(|source| RtdeError::Io {
            controller: self.settings.name.clone(),
            source,
        })
    }

    /// The first reply `wanted` accepts, within the reply time limit; data packages and other
    /// replies meanwhile are skipped.
    async fn await_reply<R>(
        &mut self,
        waiting_for: &'static str,
        wanted: impl Fn(Reply) -> Option<R>,
    ) -> Result<R, RtdeError> {
        let limit = self.settings.reply_timeout;
        let deadline = Instant::now() + limit;
        loop {
            let reply = self.next_reply(waiting_for, deadline, limit).await?;
            if let Some(found) = wanted(reply) {
                return Ok(found);
            }
        }
    }

    /// The next reply that is not a text message (those are logged), by `deadline`.
    async fn next_reply(
        &mut self,
        waiting_for: &'static str,
        deadline: Instant,
        limit: Duration,
    ) -> Result<Reply, RtdeError> {
        let controller = || self.settings.name.clone();
        loop {
            let framed = take_frame(&mut self.buffer).map_err(|source| RtdeError::Message {
                controller: controller(),
                source,
            })?;
            if let Some((kind, body)) = framed {
                match Reply::decode(kind, &body) {
                    Ok(Reply::Text(text)) => {
                        tracing::info!(controller = %self.settings.name, source = %text.source,
                            level = text.level, "{}", text.message);
                    }
                    Ok(reply) => return Ok(reply),
                    Err(source) => {
                        return Err(RtdeError::Message {
                            controller: controller(),
                            source,
                        });
                    }
                }
                continue;
            }
            let read = read_more(&mut self.stream, &mut self.buffer, deadline).await;
            read.map_err(|unread| match unread {
                Unread::Closed => RtdeError::Closed {
                    controller: controller(),
                    waiting_for,
                },
                Unread::Failed(source) => RtdeError::Io {
                    controller: controller(),
                    source,
                },
                Unread::TimedOut => RtdeError::Timeout {
                    controller: controller(),
                    waiting_for,
                    seconds: limit.as_secs_f64(),
                },
            })?;
        }
    }
}
