#pragma once

#include "ball_collision_sim/core/ball.hpp"
#include "ball_collision_sim/core/collision_event.hpp"
#include "ball_collision_sim/core/scene.hpp"
#include "ball_collision_sim/core/wall.hpp"
#include "ball_collision_sim/core/world.hpp"

#include <ball_collision_sim/AddBall.h>
#include <ball_collision_sim/AddWall.h>
#include <ball_collision_sim/BallState.h>
#include <ball_collision_sim/CollisionEvent.h>
#include <ball_collision_sim/MotionTransition.h>
#include <geometry_msgs/Quaternion.h>
#include <std_msgs/ColorRGBA.h>
#include <ball_collision_sim/Wall.h>
#include <geometry_msgs/Point.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Vector3.h>
#include <ros/time.h>

#include <string>

namespace ball_collision_sim::bridge
{
geometry_msgs::Point toPoint(const core::Vec3& v);
geometry_msgs::Vector3 toVector3(const core::Vec3& v);
core::Vec3 toVec3(const geometry_msgs::Point& p);
geometry_msgs::Quaternion toQuaternion(const core::Quat& q);
std_msgs::ColorRGBA rgba(double r, double g, double b, double a);
core::Vec3 toVec3(const geometry_msgs::Vector3& v);

/// The tf frame of a ball: prefix + "ball_<id>".
std::string ballFrame(int id, const std::string& prefix = "");

/// With the ball's angular velocity (core::World::angularVelocity()), motion kind and
/// inertia k.
ball_collision_sim::BallState toMsg(const core::Ball& ball, const core::Vec3& angular_velocity,
                                    core::MotionKind motion, double inertia);
/// balls()[k] of the world.
ball_collision_sim::BallState toMsg(const core::World& world, std::size_t k);
/// BallState's constant for a motion kind.
std::uint8_t motionConstant(core::MotionKind kind);
/// Stamped with its exact time.
ball_collision_sim::MotionTransition toMsg(const core::MotionTransition& transition, const std::string& frame_id);
/// Stamped with the exact time of impact.
ball_collision_sim::CollisionEvent toMsg(const core::CollisionEvent& event, const std::string& frame_id);
/// frame_id -> prefix + ball_<id>, with the ball's rolling orientation.
geometry_msgs::TransformStamped toTransform(const core::Ball& ball, const std::string& frame_id,
                                           const ros::Time& stamp, const std::string& prefix = "");
ball_collision_sim::Wall toMsg(const core::Wall& wall);

core::BallDef fromMsg(const ball_collision_sim::AddBall::Request& request);
core::WallDef fromMsg(const ball_collision_sim::AddWall::Request& request);
}  // namespace ball_collision_sim::bridge
