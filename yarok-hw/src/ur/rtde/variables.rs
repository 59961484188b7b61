//! The controller's RTDE variables and their types, as UR's RTDE guide lists them (the outputs
//! it sends and the inputs it takes): what a controller (or a fake one) answers to a recipe.

use super::RtdeType::{self, *};

/// Output variables with a fixed name.
const OUTPUTS: &[(&str, RtdeType)] = &[
    ("timestamp", Double),
    ("target_q", Vector6d),
    ("target_qd", Vector6d),
    ("target_qdd", Vector6d),
    ("target_current", Vector6d),
    ("target_moment", Vector6d),
    ("actual_q", Vector6d),
    ("actual_qd", Vector6d),
    ("actual_current", Vector6d),
    ("actual_current_window", Vector6d),
    ("joint_control_output", Vector6d),
    ("actual_TCP_pose", Vector6d),
    ("actual_TCP_speed", Vector6d),
    ("actual_TCP_force", Vector6d),
    ("target_TCP_pose", Vector6d),
    ("target_TCP_speed", Vector6d),
    ("actual_digital_input_bits", Uint64),
    ("joint_temperatures", Vector6d),
    ("actual_execution_time", Double),
    ("robot_mode", Int32),
    ("joint_mode", Vector6Int32),
    ("safety_mode", Int32),
    ("safety_status", Int32),
    ("actual_tool_accelerometer", Vector3d),
    ("speed_scaling", Double),
    ("target_speed_fraction", Double),
    ("actual_momentum", Double),
    ("actual_main_voltage", Double),
    ("actual_robot_voltage", Double),
    ("actual_robot_current", Double),
    ("actual_joint_voltage", Vector6d),
    ("actual_digital_output_bits", Uint64),
    ("runtime_state", Uint32),
    ("elbow_position", Vector3d),
    ("elbow_velocity", Vector3d),
    ("robot_status_bits", Uint32),
    ("safety_status_bits", Uint32),
    ("analog_io_types", Uint32),
    ("standard_analog_input0", Double),
    ("standard_analog_input1", Double),
    ("standard_analog_output0", Double),
    ("standard_analog_output1", Double),
    ("io_current", Double),
    ("euromap67_input_bits", Uint32),
    ("euromap67_output_bits", Uint32),
    ("euromap67_24V_voltage", Double),
    ("euromap67_24V_current", Double),
    ("tool_mode", Uint32),
    ("tool_analog_input_types", Uint32),
    ("tool_analog_input0", Double),
    ("tool_analog_input1", Double),
    ("tool_output_voltage", Int32),
    ("tool_output_current", Double),
    ("tool_temperature", Double),
    ("tcp_force_scalar", Double),
    ("output_bit_registers0_to_31", Uint32),
    ("output_bit_registers32_to_63", Uint32),
    ("input_bit_registers0_to_31", Uint32),
    ("input_bit_registers32_to_63", Uint32),
    ("speed_slider_mask", Uint32),
    ("speed_slider_fraction", Double),
    ("payload", Double),
    ("payload_cog", Vector3d),
    ("payload_inertia", Vector6d),
    ("script_control_line", Uint32),
    ("ft_raw_wrench", Vector6d),
    ("tool_output_mode", Uint8),
    ("tool_digital_output0_mode", Uint8),
    ("tool_digital_output1_mode", Uint8),
    ("standard_digital_output_mask", Uint8),
    ("standard_digital_output", Uint8),
    ("configurable_digital_output_mask", Uint8),
    ("configurable_digital_output", Uint8),
    ("tool_digital_output_mask", Uint8),
    ("tool_digital_output", Uint8),
];

/// Input variables with a fixed name.
const INPUTS: &[(&str, RtdeType)] = &[
    ("speed_slider_mask", Uint32),
    ("speed_slider_fraction", Double),
    ("standard_digital_output_mask", Uint8),
    ("standard_digital_output", Uint8),
    ("configurable_digital_output_mask", Uint8),
    ("configurable_digital_output", Uint8),
    ("tool_digital_output_mask", Uint8),
    ("tool_digital_output", Uint8),
    ("standard_analog_output_mask", Uint8),
    ("standard_analog_output_type", Uint8),
    ("standard_analog_output_0", Double),
    ("standard_analog_output_1", Double),
    ("input_bit_registers0_to_31", Uint32),
    ("input_bit_registers32_to_63", Uint32),
    ("external_force_torque", Vector6d),
    ("tool_analog_output_mask", Uint8),
    ("tool_analog_output_type", Uint8),
    ("tool_analog_output", Double),
];

/// Numbered registers: `{prefix}{n}` for `n` in the range, of the type.
const REGISTERS: &[(&str, std::ops::Range<u32>, RtdeType)] = &[
    ("bit_register_", 64..128, Bool),
    ("int_register_", 0..48, Int32),
    ("double_register_", 0..48, Double),
];

fn register(name: &str, side: &str) -> Option<RtdeType> {
    let rest = name.strip_prefix(side)?;
    REGISTERS.iter().find_map(|(prefix, range, rtde_type)| {
        let number: u32 = rest.strip_prefix(prefix)?.parse().ok()?;
        range.contains(&number).then_some(*rtde_type)
    })
}

/// The type of the output variable `name` (what the controller sends), if it has one.
///
/// ```
/// use yarok_hw::ur::rtde::{RtdeType, output_type};
///
/// assert_eq!(output_type("actual_q"), Some(RtdeType::Vector6d));
/// assert_eq!(output_type("output_int_register_12"), Some(RtdeType::Int32));
/// assert_eq!(output_type("actual_Q"), None); // names are case-sensitive
/// ```
pub fn output_type(name: &str) -> Option<RtdeType> {
    OUTPUTS
        .iter()
        .find(|(known, _)| *known == name)
        .map(|(_, t)| *t)
        .or_else(|| register(name, "output_"))
        .or_else(|| register(name, "input_"))
}

/// The type of the input variable `name` (what a client may send), if it has one.
pub fn input_type(name: &str) -> Option<RtdeType> {
    INPUTS
        .iter()
        .find(|(known, _)| *known == name)
        .map(|(_, t)| *t)
        .or_else(|| register(name, "input_"))
}
