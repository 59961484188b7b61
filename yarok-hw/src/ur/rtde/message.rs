//! RTDE messages (protocol version 2) and their framing: each message is `uint16 size`
//! (big-endian, counting the 3-byte header), `uint8 type`, then its body. The same type byte
//! names a request and its reply, so each direction has its own type: [`Request`] (client to
//! controller) and [`Reply`] (controller to client).

/// The longest message the size field can carry, header included.
pub const MAX_MESSAGE: usize = u16::MAX as usize;

/// Header bytes: size and type.
const HEADER: usize = 3;

const PROTOCOL_VERSION: u8 = b'V';
const CONTROLLER_VERSION: u8 = b'v';
const TEXT: u8 = b'M';
const DATA: u8 = b'U';
const SETUP_OUTPUTS: u8 = b'O';
const SETUP_INPUTS: u8 = b'I';
const START: u8 = b'S';
const PAUSE: u8 = b'P';

/// The controller's software version (`v`): 3.x on CB3 controllers, 5.x on e-Series.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ControllerVersion {
    /// Major version.
    pub major: u32,
    /// Minor version.
    pub minor: u32,
    /// Bug-fix version.
    pub bugfix: u32,
    /// Build number.
    pub build: u32,
}

impl std::fmt::Display for ControllerVersion {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Self {
            major,
            minor,
            bugfix,
            build,
        } = self;
        write!(f, "{major}.{minor}.{bugfix}.{build}")
    }
}

/// A text message (`M`), either way.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Text {
    /// The message.
    pub message: String,
    /// Who sends it.
    pub source: String,
    /// 0 exception, 1 error, 2 warning, 3 info.
    pub level: u8,
}

/// A message from a client to the controller.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Request {
    /// `V`: use this protocol version (yarok speaks 2).
    ProtocolVersion(u16),
    /// `v`: what is the controller's version?
    ControllerVersion,
    /// `O`: send these variables at this rate (Hz).
    SetupOutputs {
        /// Packages a second.
        frequency: f64,
        /// The variables, in package order.
        names: Vec<String>,
    },
    /// `I`: these variables will come in data packages.
    SetupInputs {
        /// The variables, in package order.
        names: Vec<String>,
    },
    /// `S`: start sending outputs.
    Start,
    /// `P`: pause.
    Pause,
    /// `U`: values of an input recipe.
    Data {
        /// The input recipe's id.
        recipe: u8,
        /// Its values, encoded.
        payload: Vec<u8>,
    },
    /// `M`.
    Text(Text),
}

/// A message from the controller to a client.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Reply {
    /// `V`: whether the protocol version was accepted.
    ProtocolVersion {
        /// Accepted.
        accepted: bool,
    },
    /// `v`.
    ControllerVersion(ControllerVersion),
    /// `O`: the output recipe's id (0: a variable was not found) and each variable's type
    /// name, `NOT_FOUND` for an unknown one.
    OutputsSetUp {
        /// The recipe's id.
        recipe: u8,
        /// A type name a variable.
        types: Vec<String>,
    },
    /// `I`: the input recipe's id and each variable's type name, `IN_USE` for one another
    /// client writes, `NOT_FOUND` for an unknown one.
    InputsSetUp {
        /// The recipe's id.
        recipe: u8,
        /// A type name a variable.
        types: Vec<String>,
    },
    /// `S`: whether outputs start.
    Started {
        /// Accepted.
        accepted: bool,
    },
    /// `P`: whether outputs pause.
    Paused {
        /// Accepted.
        accepted: bool,
    },
    /// `U`: values of the output recipe.
    Data {
        /// The output recipe's id.
        recipe: u8,
        /// Its values, encoded.
        payload: Vec<u8>,
    },
    /// `M`.
    Text(Text),
}

/// A message could not be framed or read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum MessageError {
    /// The size field is smaller than the header.
    #[error("a message size of {0} bytes is less than its 3-byte header")]
    Size(u16),
    /// The body is too long for the size field.
    #[error("a message of {0} bytes does not fit RTDE's 16-bit size")]
    TooLong(usize),
    /// The type byte names no message this side receives.
    #[error("unknown message type {0:#04x}")]
    UnknownType(u8),
    /// The body is shorter than its type needs.
    #[error("a `{kind}` message of {got} bytes is too short (needs {needed})")]
    Truncated {
        /// The type, as a character.
        kind: char,
        /// Bytes it needs.
        needed: usize,
        /// Bytes it has.
        got: usize,
    },
    /// A text field is not UTF-8 or a length field runs past the body.
    #[error("a `{0}` message's text is malformed")]
    Text(char),
    /// A recipe set-up reply does not fit the request.
    #[error("a recipe reply is malformed: {0}")]
    Recipe(String),
}

/// The first whole message at the front of `buffer`, removed from it: its type and body;
/// `None` while the message is still incomplete.
///
/// # Errors
///
/// [`MessageError::Size`] when the size field is impossible (the stream is out of step).
pub fn take_frame(buffer: &mut Vec<u8>) -> Result<Option<(u8, Vec<u8>)>, MessageError> {
    let Some(header) = buffer.get(..HEADER) else {
        return Ok(None);
    };
    let size = u16::from_be_bytes([header[0], header[1]]);
    if usize::from(size) < HEADER {
        return Err(MessageError::Size(size));
    }
    if buffer.len() < usize::from(size) {
        return Ok(None);
    }
    let kind = buffer[2];
    let body = buffer[HEADER..usize::from(size)].to_vec();
    buffer.drain(..usize::from(size));
    Ok(Some((kind, body)))
}

/// A whole message: header and body.
fn frame(kind: u8, body: &[u8]) -> Result<Vec<u8>, MessageError> {
    let size = body.len() + HEADER;
    let size16 = u16::try_from(size).map_err(|_| MessageError::TooLong(size))?;
    let mut out = Vec::with_capacity(size);
    out.extend_from_slice(&size16.to_be_bytes());
    out.push(kind);
    out.extend_from_slice(body);
    Ok(out)
}

/// Names or types as the protocol joins them: comma-separated.
fn joined(items: &[String]) -> Vec<u8> {
    items.join(",").into_bytes()
}

/// Comma-separated items; an empty body holds none.
fn split(kind: u8, body: &[u8]) -> Result<Vec<String>, MessageError> {
    let text = std::str::from_utf8(body).map_err(|_| MessageError::Text(char::from(kind)))?;
    Ok(if text.is_empty() {
        Vec::new()
    } else {
        text.split(',').map(str::to_owned).collect()
    })
}

fn need(kind: u8, body: &[u8], needed: usize) -> Result<(), MessageError> {
    if body.len() < needed {
        return Err(MessageError::Truncated {
            kind: char::from(kind),
            needed,
            got: body.len(),
        });
    }
    Ok(())
}

fn flag(kind: u8, body: &[u8]) -> Result<bool, MessageError> {
    need(kind, body, 1)?;
    Ok(body[0] != 0)
}

impl Text {
    fn encode(&self) -> Vec<u8> {
        let clip = |text: &str| -> Vec<u8> {
            let mut end = text.len().min(usize::from(u8::MAX));
            while !text.is_char_boundary(end) {
                end -= 1;
            }
            text.as_bytes()[..end].to_vec()
        };
        let (message, source) = (clip(&self.message), clip(&self.source));
        let mut out = Vec::with_capacity(message.len() + source.len() + 3);
        out.push(message.len() as u8);
        out.extend_from_slice(&message);
        out.push(source.len() as u8);
        out.extend_from_slice(&source);
        out.push(self.level);
        out
    }

    fn decode(body: &[u8]) -> Result<Self, MessageError> {
        let malformed = || MessageError::Text(char::from(TEXT));
        let mut rest = body;
        let mut field = || -> Result<String, MessageError> {
            let (&length, after) = rest.split_first().ok_or_else(malformed)?;
            let text = after.get(..usize::from(length)).ok_or_else(malformed)?;
            rest = &after[usize::from(length)..];
            String::from_utf8(text.to_vec()).map_err(|_| malformed())
        };
        let message = field()?;
        let source = field()?;
        let level = *rest.first().ok_or_else(malformed)?;
        Ok(Self {
            message,
            source,
            level,
        })
    }
}

impl Request {
    /// The whole message, header included. Text longer than 255 bytes is cut.
    ///
    /// # Errors
    ///
    /// [`MessageError::TooLong`] when it does not fit the size field.
    pub fn encode(&self) -> Result<Vec<u8>, MessageError> {
        match self {
            Request::ProtocolVersion(version) => frame(PROTOCOL_VERSION, &version.to_be_bytes()),
            Request::ControllerVersion => frame(CONTROLLER_VERSION, &[]),
            Request::SetupOutputs { frequency, names } => {
                let mut body = frequency.to_be_bytes().to_vec();
                body.extend(joined(names));
                frame(SETUP_OUTPUTS, &body)
            }
            Request::SetupInputs { names } => frame(SETUP_INPUTS, &joined(names)),
            Request::Start => frame(START, &[]),
            Request::Pause => frame(PAUSE, &[]),
            Request::Data { recipe, payload } => {
                let mut body = vec![*recipe];
                body.extend_from_slice(payload);
                frame(DATA, &body)
            }
            Request::Text(text) => frame(TEXT, &text.encode()),
        }
    }

    /// The request of type `kind` whose body is `body` (as a controller reads it).
    ///
    /// # Errors
    ///
    /// [`MessageError`] for an unknown type or a malformed body.
    pub fn decode(kind: u8, body: &[u8]) -> Result<Self, MessageError> {
        Ok(match kind {
            PROTOCOL_VERSION => {
                need(kind, body, 2)?;
                Request::ProtocolVersion(u16::from_be_bytes([body[0], body[1]]))
            }
            CONTROLLER_VERSION => Request::ControllerVersion,
            SETUP_OUTPUTS => {
                need(kind, body, 8)?;
                let frequency = f64::from_be_bytes(body[..8].try_into().expect("8 bytes"));
                Request::SetupOutputs {
                    frequency,
                    names: split(kind, &body[8..])?,
                }
            }
            SETUP_INPUTS => Request::SetupInputs {
                names: split(kind, body)?,
            },
            START => Request::Start,
            PAUSE => Request::Pause,
            DATA => {
                need(kind, body, 1)?;
                Request::Data {
                    recipe: body[0],
                    payload: body[1..].to_vec(),
                }
            }
            TEXT => Request::Text(Text::decode(body)?),
            other => return Err(MessageError::UnknownType(other)),
        })
    }
}

impl Reply {
    /// The whole message, header included. Text longer than 255 bytes is cut.
    ///
    /// # Errors
    ///
    /// [`MessageError::TooLong`] when it does not fit the size field.
    pub fn encode(&self) -> Result<Vec<u8>, MessageError> {
        let setup = |recipe: u8, types: &[String]| {
            let mut body = vec![recipe];
            body.extend(joined(types));
            body
        };
        match self {
            Reply::ProtocolVersion { accepted } => frame(PROTOCOL_VERSION, &[u8::from(*accepted)]),
            Reply::ControllerVersion(version) => {
                let body: Vec<u8> = [version.major, version.minor, version.bugfix, version.build]
                    .iter()
                    .flat_map(|part| part.to_be_bytes())
                    .collect();
                frame(CONTROLLER_VERSION, &body)
            }
            Reply::OutputsSetUp { recipe, types } => frame(SETUP_OUTPUTS, &setup(*recipe, types)),
            Reply::InputsSetUp { recipe, types } => frame(SETUP_INPUTS, &setup(*recipe, types)),
            Reply::Started { accepted } => frame(START, &[u8::from(*accepted)]),
            Reply::Paused { accepted } => frame(PAUSE, &[u8::from(*accepted)]),
            Reply::Data { recipe, payload } => {
                let mut body = vec![*recipe];
                body.extend_from_slice(payload);
                frame(DATA, &body)
            }
            Reply::Text(text) => frame(TEXT, &text.encode()),
        }
    }

    /// The reply of type `kind` whose body is `body` (as a client reads it).
    ///
    /// # Errors
    ///
    /// [`MessageError`] for an unknown type or a malformed body.
    pub fn decode(kind: u8, body: &[u8]) -> Result<Self, MessageError> {
        let setup = |body: &[u8]| -> Result<(u8, Vec<String>), MessageError> {
            need(kind, body, 1)?;
            Ok((body[0], split(kind, &body[1..])?))
        };
        Ok(match kind {
            PROTOCOL_VERSION => Reply::ProtocolVersion {
                accepted: flag(kind, body)?,
            },
            CONTROLLER_VERSION => {
                need(kind, body, 16)?;
                let part = |i: usize| {
                    u32::from_be_bytes(body[4 * i..4 * i + 4].try_into().expect("4 bytes"))
                };
                Reply::ControllerVersion(ControllerVersion {
                    major: part(0),
                    minor: part(1),
                    bugfix: part(2),
                    build: part(3),
                })
            }
            SETUP_OUTPUTS => {
                let (recipe, types) = setup(body)?;
                Reply::OutputsSetUp { recipe, types }
            }
            SETUP_INPUTS => {
                let (recipe, types) = setup(body)?;
                Reply::InputsSetUp { recipe, types }
            }
            START => Reply::Started {
                accepted: flag(kind, body)?,
            },
            PAUSE => Reply::Paused {
                accepted: flag(kind, body)?,
            },
            DATA => {
                need(kind, body, 1)?;
                Reply::Data {
                    recipe: body[0],
                    payload: body[1..].to_vec(),
                }
            }
            TEXT => Reply::Text(Text::decode(body)?),
            other => return Err(MessageError::UnknownType(other)),
        })
    }
}
