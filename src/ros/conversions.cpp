#include "ball_collision_sim/ros/conversions.hpp"

namespace ball_collision_sim::bridge
{
geometry_msgs::Point toPoint(const core::Vec3& v)
{
  geometry_msgs::Point p;
  p.x = v.x();
  p.y = v.y();
  p.z = v.z();
  return p;
}

geometry_msgs::Vector3 toVector3(const core::Vec3& v)
{
  geometry_msgs::Vector3 out;
  out.x = v.x();
  out.y = v.y();
  out.z = v.z();
  return out;
}

core::Vec3 toVec3(const geometry_msgs::Point& p)
{
  return core::Vec3(p.x, p.y, p.z);
}

core::Vec3 toVec3(const geometry_msgs::Vector3& v)
{
  return core::Vec3(v.x, v.y, v.z);
}

std::string ballFrame(int id, const std::string& prefix)
{
  return prefix + "ball_" + std::to_string(id);
}

geometry_msgs::Quaternion toQuaternion(const core::Quat& q)
{
  geometry_msgs::Quaternion out;
  out.x = q.x();
  out.y = q.y();
  out.z = q.z();
  out.w = q.w();
  return out;
}

std_msgs::ColorRGBA rgba(double r, double g, double b, double a)
{
  std_msgs::ColorRGBA c;
  c.r = static_cast<float>(r);
  c.g = static_cast<float>(g);
  c.b = static_cast<float>(b);
  c.a = static_cast<float>(a);
  return c;
}

std::uint8_t motionConstant(core::MotionKind kind)
{
  switch (kind)
  {
    case core::MotionKind::kSliding:
      return ball_collision_sim::BallState::SLIDING;
    case core::MotionKind::kRolling:
      return ball_collision_sim::BallState::ROLLING;
    case core::MotionKind::kSpinning:
      return ball_collision_sim::BallState::SPINNING;
    case core::MotionKind::kStationary:
      return ball_collision_sim::BallState::STATIONARY;
    case core::MotionKind::kFlying:
      return ball_collision_sim::BallState::FLYING;
  }
  return ball_collision_sim::BallState::STATIONARY;
}

ball_collision_sim::BallState toMsg(const core::World& world, std::size_t k)
{
  return toMsg(world.balls()[k], world.angularVelocity(k), world.motionKind(k), world.inertia(k));
}

ball_collision_sim::MotionTransition toMsg(const core::MotionTransition& transition, const std::string& frame_id)
{
  ball_collision_sim::MotionTransition msg;
  msg.header.stamp = ros::Time(transition.time);
  msg.header.frame_id = frame_id;
  msg.ball = transition.ball;
  msg.before = motionConstant(transition.from);
  msg.after = motionConstant(transition.to);
  return msg;
}

ball_collision_sim::BallState toMsg(const core::Ball& ball, const core::Vec3& angular_velocity, core::MotionKind motion,
                                    double inertia)
{
  ball_collision_sim::BallState msg;
  msg.id = ball.id;
  msg.radius = ball.radius;
  msg.mass = ball.mass;
  msg.pose.position = toPoint(ball.position);
  msg.pose.orientation = toQuaternion(ball.orientation);
  msg.twist.linear = toVector3(ball.velocity);
  msg.twist.angular = toVector3(angular_velocity);
  msg.motion = motionConstant(motion);
  msg.inertia = inertia;
  return msg;
}

ball_collision_sim::CollisionEvent toMsg(const core::CollisionEvent& event, const std::string& frame_id)
{
  ball_collision_sim::CollisionEvent msg;
  msg.header.stamp = ros::Time(event.time);
  msg.header.frame_id = frame_id;
  switch (event.kind)
  {
    case core::CollisionEvent::Kind::kBallBall:
      msg.kind = msg.BALL_BALL;
      break;
    case core::CollisionEvent::Kind::kBallWall:
      msg.kind = msg.BALL_WALL;
      break;
    case core::CollisionEvent::Kind::kBallFloor:
      msg.kind = msg.BALL_FLOOR;
      break;
  }
  msg.ball = event.ball;
  msg.other = event.other;
  switch (event.feature)
  {
    case core::WallFeature::kFace:
      msg.feature = msg.FACE;
      break;
    case core::WallFeature::kEdge:
      msg.feature = msg.EDGE;
      break;
    case core::WallFeature::kCorner:
      msg.feature = msg.CORNER;
      break;
  }
  msg.point = toPoint(event.point);
  msg.normal = toVector3(event.normal);
  msg.impulse = event.impulse;
  msg.approach_speed = event.approach_speed;
  msg.resting = event.resting;
  return msg;
}

ball_collision_sim::Wall toMsg(const core::Wall& wall)
{
  ball_collision_sim::Wall msg;
  msg.id = wall.id;
  msg.point = toPoint(wall.def.point);
  msg.u = toVector3(wall.def.u);
  msg.v = toVector3(wall.def.v);
  msg.restitution = wall.restitution;
  return msg;
}

geometry_msgs::TransformStamped toTransform(const core::Ball& ball, const std::string& frame_id,
                                           const ros::Time& stamp, const std::string& prefix)
{
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = frame_id;
  t.child_frame_id = ballFrame(ball.id, prefix);
  t.transform.translation = toVector3(ball.position);
  t.transform.rotation = toQuaternion(ball.orientation);
  return t;
}

core::BallDef fromMsg(const ball_collision_sim::AddBall::Request& request)
{
  core::BallDef def;
  def.position = toVec3(request.position);
  def.velocity = toVec3(request.velocity);
  def.radius = request.radius;
  def.mass = request.mass;
  if (request.set_angular_velocity)
    def.angular_velocity = toVec3(request.angular_velocity);
  if (request.inertia != 0)
    def.inertia = request.inertia;  // (checked with the ball: in [0.01, 1])
  return def;
}

core::WallDef fromMsg(const ball_collision_sim::AddWall::Request& request)
{
  core::WallDef def;
  def.point = toVec3(request.point);
  def.u = toVec3(request.u);
  def.v = toVec3(request.v);
  return def;
}
}  // namespace ball_collision_sim::bridge
