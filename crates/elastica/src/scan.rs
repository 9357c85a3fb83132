pub struct ClosedFormScan;
pub struct ScanPoint;
pub enum Phase0End {}
