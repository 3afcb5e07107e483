//! What every table report of its own format (Szentandrási's Table 1, the SRAA table) opens
//! with: the format version, the table, the command, the program and the device, and whether
//! the frames were presented.

use crate::vk::DeviceInfo;
use serde::Serialize;

#[derive(Clone, Debug, Serialize)]
pub struct TableRun {
    pub version: u32,
    pub table: &'static str,
    pub command: String,
    pub ssgi_version: &'static str,
    pub device: String,
    pub driver: String,
    pub device_type: String,
    pub window: bool,
    pub present_mode: Option<&'static str>,
}

impl TableRun {
    /// Version 1 of `table`'s format, run by `command` on `device`; `present_mode` is the
    /// window's (`None` offscreen).
    pub fn new(
        table: &'static str,
        command: String,
        device: &DeviceInfo,
        present_mode: Option<&'static str>,
    ) -> Self {
        Self {
            version: 1,
            table,
            command,
            ssgi_version: env!("CARGO_PKG_VERSION"),
            device: device.name.clone(),
            driver: device.driver.clone(),
            device_type: device.device_type.clone(),
            window: present_mode.is_some(),
            present_mode,
        }
    }
}
