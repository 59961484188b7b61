//! RTDE messages byte for byte: every request and reply as the controller and the clients
//! put them on the wire, framing across partial reads, data packages through their recipes;
//! then 100 000 generated packets — well-formed ones mutated, and arbitrary bytes — through the
//! framing and both decoders, never a panic, and every well-formed message decoding to itself.

use yarok_test::generator;

use generator::Generator;
use yarok_hw::ur::rtde::{
    ControllerVersion, MessageError, Recipe, RecipeError, Reply, Request, RtdeType, Text, Value,
    take_frame,
};

fn names(list: &[&str]) -> Vec<String> {
    list.iter().map(|&name| name.to_owned()).collect()
}

#[test]
fn requests_byte_for_byte() {
    let cases: Vec<(Request, Vec<u8>)> = vec![
        (Request::ProtocolVersion(2), vec![0, 5, b'V', 0, 2]),
        (Request::ControllerVersion, vec![0, 3, b'v']),
        (Request::Start, vec![0, 3, b'S']),
        (Request::Pause, vec![0, 3, b'P']),
        (
            Request::SetupOutputs {
                frequency: 125.0,
                names: names(&["timestamp", "actual_q"]),
            },
            [
                &[0, 29, b'O'][..],
                &[0x40, 0x5F, 0x40, 0, 0, 0, 0, 0],
                b"timestamp,actual_q",
            ]
            .concat(),
        ),
        (
            Request::SetupInputs {
                names: names(&["input_int_register_24"]),
            },
            [&[0, 24, b'I'][..], b"input_int_register_24"].concat(),
        ),
        (
            Request::Data {
                recipe: 1,
                payload: vec![0, 0, 0, 7],
            },
            vec![0, 8, b'U', 1, 0, 0, 0, 7],
        ),
        (
            Request::Text(Text {
                message: "hi".into(),
                source: "yarok".into(),
                level: 3,
            }),
            [&[0, 13, b'M', 2][..], b"hi", &[5], b"yarok", &[3]].concat(),
        ),
    ];
    for (request, bytes) in cases {
        assert_eq!(request.encode().unwrap(), bytes, "{request:?}");
        let mut buffer = bytes.clone();
        let (kind, body) = take_frame(&mut buffer).unwrap().unwrap();
        assert!(buffer.is_empty());
        assert_eq!(Request::decode(kind, &body).unwrap(), request);
    }
}

#[test]
fn replies_byte_for_byte() {
    let version = ControllerVersion {
        major: 5,
        minor: 11,
        bugfix: 1,
        build: 108_318,
    };
    let cases: Vec<(Reply, Vec<u8>)> = vec![
        (
            Reply::ProtocolVersion { accepted: true },
            vec![0, 4, b'V', 1],
        ),
        (
            Reply::ControllerVersion(version),
            vec![
                0, 19, b'v', 0, 0, 0, 5, 0, 0, 0, 11, 0, 0, 0, 1, 0, 1, 0xA7, 0x1E,
            ],
        ),
        (
            Reply::OutputsSetUp {
                recipe: 1,
                types: names(&["DOUBLE", "VECTOR6D"]),
            },
            [&[0, 19, b'O', 1][..], b"DOUBLE,VECTOR6D"].concat(),
        ),
        (
            Reply::InputsSetUp {
                recipe: 2,
                types: names(&["IN_USE"]),
            },
            [&[0, 10, b'I', 2][..], b"IN_USE"].concat(),
        ),
        (Reply::Started { accepted: true }, vec![0, 4, b'S', 1]),
        (Reply::Paused { accepted: false }, vec![0, 4, b'P', 0]),
        (
            Reply::Data {
                recipe: 1,
                payload: vec![9; 8],
            },
            [&[0, 12, b'U', 1][..], &[9; 8]].concat(),
        ),
    ];
    for (reply, bytes) in cases {
        assert_eq!(reply.encode().unwrap(), bytes, "{reply:?}");
        let mut buffer = bytes.clone();
        let (kind, body) = take_frame(&mut buffer).unwrap().unwrap();
        assert_eq!(Reply::decode(kind, &body).unwrap(), reply);
    }
    assert_eq!(version.to_string(), "5.11.1.108318");
}

#[test]
fn frames_come_whole_across_partial_reads_and_bad_ones_are_errors() {
    let stream = [
        Reply::Started { accepted: true }.encode().unwrap(),
        Reply::Data {
            recipe: 1,
            payload: vec![1, 2, 3],
        }
        .encode()
        .unwrap(),
    ]
    .concat();
    let mut buffer = Vec::new();
    let mut frames = Vec::new();
    for byte in stream {
        buffer.push(byte);
        while let Some(frame) = take_frame(&mut buffer).unwrap() {
            frames.push(frame);
        }
    }
    assert_eq!(frames, [(b'S', vec![1]), (b'U', vec![1, 1, 2, 3])]);

    assert_eq!(
        take_frame(&mut vec![0, 2, b'U']),
        Err(MessageError::Size(2))
    );
    assert!(matches!(
        Reply::decode(b'v', &[0, 0, 0, 5]),
        Err(MessageError::Truncated {
            kind: 'v',
            needed: 16,
            got: 4
        })
    ));
    assert_eq!(
        Reply::decode(b'x', &[]),
        Err(MessageError::UnknownType(b'x'))
    );
    assert_eq!(
        Reply::decode(b'M', &[9, b'a']),
        Err(MessageError::Text('M'))
    );
    let too_long = Request::SetupInputs {
        names: vec!["x".repeat(70_000)],
    };
    assert_eq!(too_long.encode(), Err(MessageError::TooLong(70_003)));
}

#[test]
fn data_packages_through_their_recipes() {
    let recipe = Recipe {
        id: 3,
        variables: vec![
            ("timestamp".into(), RtdeType::Double),
            ("actual_q".into(), RtdeType::Vector6d),
            ("robot_mode".into(), RtdeType::Int32),
            ("joint_mode".into(), RtdeType::Vector6Int32),
            ("robot_status_bits".into(), RtdeType::Uint32),
            ("actual_digital_input_bits".into(), RtdeType::Uint64),
            ("payload_cog".into(), RtdeType::Vector3d),
            ("output_bit_register_64".into(), RtdeType::Bool),
            ("tool_output_mode".into(), RtdeType::Uint8),
            ("x".into(), RtdeType::Vector6Uint32),
        ],
    };
    let values = vec![
        Value::Double(1.5),
        Value::Vector6d([0.1, -1.2, 1.3, -1.4, 1.5, -1.6]),
        Value::Int32(-1),
        Value::Vector6Int32([253; 6]),
        Value::Uint32(0b1011),
        Value::Uint64(1 << 40),
        Value::Vector3d([0.0, 0.0, 0.05]),
        Value::Bool(true),
        Value::Uint8(2),
        Value::Vector6Uint32([1, 2, 3, 4, 5, 6]),
    ];
    let payload = recipe.encode(&values).unwrap();
    assert_eq!(payload.len(), recipe.size());
    assert_eq!(payload.len(), 8 + 48 + 4 + 24 + 4 + 8 + 24 + 1 + 1 + 24);
    assert_eq!(&payload[..8], &1.5f64.to_be_bytes());
    assert_eq!(&payload[56..60], &[0xFF; 4]);
    assert_eq!(recipe.decode(&payload).unwrap(), values);

    assert_eq!(
        recipe.decode(&payload[1..]),
        Err(RecipeError::Length {
            recipe: 3,
            expected: payload.len(),
            got: payload.len() - 1
        })
    );
    let mut wrong = values.clone();
    wrong[2] = Value::Double(7.0);
    assert!(matches!(
        recipe.encode(&wrong),
        Err(RecipeError::Type {
            expected: "INT32",
            got: "DOUBLE",
            ..
        })
    ));
    assert!(matches!(
        recipe.encode(&values[..2]),
        Err(RecipeError::Count {
            expected: 10,
            got: 2,
            ..
        })
    ));
}

/// RTDE replies from the generator.
trait Replies {
    fn word(&mut self) -> String;
    fn words(&mut self) -> Vec<String>;
    fn reply(&mut self) -> Reply;
}

impl Replies for Generator {
    fn word(&mut self) -> String {
        let words = [
            "actual_q",
            "timestamp",
            "DOUBLE",
            "",
            "NOT_FOUND",
            "é",
            "a,b",
        ];
        words[self.below(words.len())].to_owned()
    }

    fn words(&mut self) -> Vec<String> {
        (0..self.below(4)).map(|_| self.word()).collect()
    }

    fn reply(&mut self) -> Reply {
        match self.below(8) {
            0 => Reply::ProtocolVersion {
                accepted: self.next_u64().is_multiple_of(2),
            },
            1 => Reply::ControllerVersion(ControllerVersion {
                major: self.next_u64() as u32,
                minor: self.next_u64() as u32,
                bugfix: self.next_u64() as u32,
                build: self.next_u64() as u32,
            }),
            2 => Reply::OutputsSetUp {
                recipe: self.next_u64() as u8,
                types: self.words(),
            },
            3 => Reply::InputsSetUp {
                recipe: self.next_u64() as u8,
                types: self.words(),
            },
            4 => Reply::Started {
                accepted: self.next_u64().is_multiple_of(2),
            },
            5 => Reply::Paused {
                accepted: self.next_u64().is_multiple_of(2),
            },
            6 => {
                let length = self.below(64);
                Reply::Data {
                    recipe: self.next_u64() as u8,
                    payload: self.bytes(length),
                }
            }
            _ => Reply::Text(Text {
                message: self.word(),
                source: self.word(),
                level: self.next_u64() as u8,
            }),
        }
    }
}

/// Whether `list` survives being joined with commas and split again.
fn splits_back(list: &[String]) -> bool {
    !list
        .iter()
        .any(|item| item.contains(',') || item.is_empty())
}

#[test]
fn a_hundred_thousand_generated_packets_never_panic() {
    let mut generator = Generator(0x9E37_79B9_7F4A_7C15);
    let mut decoded = 0;
    for round in 0..100_000 {
        let reply = generator.reply();
        let mut bytes = reply.encode().unwrap();
        let pristine = round % 3 == 0;
        if !pristine {
            // Flip, cut or extend: what a broken stream might hold.
            match generator.below(3) {
                0 => {
                    let at = generator.below(bytes.len());
                    bytes[at] ^= generator.next_u64() as u8 | 1;
                }
                1 => bytes.truncate(generator.below(bytes.len())),
                _ => {
                    let extra = generator.below(8);
                    bytes.extend(generator.bytes(extra));
                }
            }
        }
        if round % 7 == 0 {
            let length = generator.below(40);
            bytes = generator.bytes(length);
        }
        let mut buffer = bytes.clone();
        while let Ok(Some((kind, body))) = take_frame(&mut buffer) {
            let as_reply = Reply::decode(kind, &body);
            let _as_request = Request::decode(kind, &body);
            if pristine && round % 7 != 0 {
                let expected_back = match &reply {
                    Reply::OutputsSetUp { types, .. } | Reply::InputsSetUp { types, .. } => {
                        splits_back(types)
                    }
                    _ => true,
                };
                if expected_back {
                    assert_eq!(as_reply.as_ref(), Ok(&reply), "{bytes:?}");
                    decoded += 1;
                }
            }
        }
    }
    assert!(decoded > 10_000, "only {decoded} packets decoded back");
}
