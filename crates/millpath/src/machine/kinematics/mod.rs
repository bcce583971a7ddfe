//! Kinematics of 3- and 5-axis machines: forward, inverse, Jacobian.
