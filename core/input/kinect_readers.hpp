#pragma once
// Readers of real Kinect v2 skeleton data (docs/model.md section 8). Both formats use the Kinect v2 JointType
// order, so the hands are joints 7 (HandLeft) and 11 (HandRight). A joint's TrackingState maps
// to a frame as: 2 tracked -> sample, 1 inferred -> sample marked inferred, 0 -> no sample.
#include <array>
#include <string>

#include "core/input/recording.hpp"

namespace drape {

/// Kinect v2 JointType names, index = joint number.
extern const std::array<const char*, 25> kinect_joint_names;
/// Joint number of the left hand in the Kinect v2 order.
inline constexpr int kinect_hand_left = 7;
/// Joint number of the right hand in the Kinect v2 order.
inline constexpr int kinect_hand_right = 11;

/// Reads a Kinect v2 body-frame CSV (KinectReader tool): per line a timestamp in 100 ns ticks
/// and 25 joints as X, Y, Z, TrackingState, with an optional trailing comma. Times are
/// seconds relative to the first frame.
Recording read_kinect_v2_csv(const std::string& file);

/// Reads an NTU RGB+D `.skeleton` file (30 frames per second, frame i at t = i/30). The hands
/// are those of the first body of the first frame that has one, followed through the file by
/// its body ID; frames without that body have no hands (another person is never substituted).
Recording read_ntu_skeleton(const std::string& file);

}  // namespace drape
