// sandtin-haptic-replay: a stand-in for a hardware driver process. It plays a trajectory file
// over the sandtin haptic UDP protocol (engine/haptics/udp_protocol.hpp) to a running session
// and logs the forces it gets back; it can also author synthetic trajectories.
//
//   sandtin-haptic-replay play TRAJ --port P [--host 127.0.0.1] [--rate HZ] [--lockstep]
//                              [--timeout-ms 1000] [--log forces.csv]
//   sandtin-haptic-replay synth (stroke | circles) -o TRAJ [--surface Z] [--depth D]
//                              [--seconds S]
//
// play sends pose i with sequence i + 1 at the trajectory's rate (or --rate). With --lockstep
// it waits for the force that acknowledges each pose before sending the next (so every pose is
// answered; what a test wants), otherwise it never waits (what a real driver does). At the end
// it sends a bye packet and prints a JSON summary; the log has one line per force received:
// ack, the pose it answers, flags and the force. Exit code 0 when every pose was answered
// (lockstep) or at least one force arrived (free-running), 1 otherwise, 2 for usage errors.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "geom/vec3.hpp"
#include "haptics/trajectory.hpp"
#include "haptics/udp_protocol.hpp"
#include "haptics/udp_socket.hpp"

namespace {

using namespace sandtin::haptics;

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

constexpr const char* kUsage =
    "usage: sandtin-haptic-replay play TRAJ --port P [--host 127.0.0.1] [--rate HZ] "
    "[--lockstep] [--timeout-ms MS] [--log forces.csv]\n"
    "       sandtin-haptic-replay synth (stroke | circles) -o TRAJ [--surface Z] [--depth D] "
    "[--seconds S]\n";

struct Options {
    std::vector<std::string> positionals;
    std::map<std::string, std::string> values;
    bool has(const std::string& k) const { return values.count(k) > 0; }
    double number(const std::string& k, double fallback) const {
        if (!has(k)) return fallback;
        try {
            std::size_t used = 0;
            const double v = std::stod(values.at(k), &used);
            if (used != values.at(k).size()) throw std::invalid_argument(k);
            return v;
        } catch (const std::exception&) {
            throw UsageError(k + " needs a number, got '" + values.at(k) + "'");
        }
    }
};

Options parse(int argc, char** argv) {
    static const std::map<std::string, bool> kTakesValue = {
        {"--port", true},       {"--host", true},   {"--rate", true}, {"--lockstep", false},
        {"--timeout-ms", true}, {"--log", true},    {"-o", true},     {"--surface", true},
        {"--depth", true},      {"--seconds", true}};
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a.size() > 1 && a[0] == '-') {
            const auto it = kTakesValue.find(a);
            if (it == kTakesValue.end()) throw UsageError("unknown option " + a);
            if (it->second) {
                if (i + 1 >= argc) throw UsageError(a + " needs a value");
                o.values[a] = argv[++i];
            } else {
                o.values[a] = "";
            }
        } else {
            o.positionals.push_back(a);
        }
    }
    return o;
}

int synth(const Options& o) {
    if (o.positionals.size() != 2 || !o.has("-o")) throw UsageError("synth needs a kind and -o");
    Trajectory t;
    if (o.positionals[1] == "stroke") {
        StrokeTrajectorySpec s;
        s.surface = o.number("--surface", s.surface);
        s.depth = o.number("--depth", s.depth);
        t = make_stroke_trajectory(s);
    } else if (o.positionals[1] == "circles") {
        CircleTrajectorySpec s;
        s.surface = o.number("--surface", s.surface);
        s.depth = o.number("--depth", s.depth);
        s.seconds = o.number("--seconds", s.seconds);
        t = make_circle_trajectory(s);
    } else {
        throw UsageError("unknown trajectory kind '" + o.positionals[1] + "' (stroke, circles)");
    }
    save_trajectory(o.values.at("-o"), t);
    std::cout << "{\"samples\": " << t.samples.size() << ", \"rate_hz\": " << t.rate_hz << "}\n";
    return 0;
}

int play(const Options& o) {
    if (o.positionals.size() != 2 || !o.has("--port"))
        throw UsageError("play needs TRAJ and --port");
    const Trajectory t = load_trajectory(o.positionals[1]);
    const double port_number = o.number("--port", 0);
    if (!(port_number >= 1 && port_number <= 65535)) throw UsageError("--port must be in 1..65535");
    const UdpEndpoint to{parse_ipv4(o.has("--host") ? o.values.at("--host") : "127.0.0.1"),
                         static_cast<std::uint16_t>(port_number)};
    const double rate = o.number("--rate", t.rate_hz);
    if (!(rate > 0.0) || rate > 100000.0) throw UsageError("--rate must be in (0, 1e5]");
    const double timeout_ms = o.number("--timeout-ms", 1000.0);
    if (!(timeout_ms >= 1.0)) throw UsageError("--timeout-ms must be >= 1");
    const bool lockstep = o.has("--lockstep");
    std::ofstream log;
    if (o.has("--log")) {
        log.open(o.values.at("--log"));
        if (!log) throw std::runtime_error("cannot write " + o.values.at("--log"));
        log << "ack,x,y,z,buttons,flags,fx,fy,fz\n";
        log.precision(17);
    }

    UdpSocket socket = UdpSocket::bind(0);
    std::array<std::uint8_t, 256> buffer{};
    std::uint64_t forces = 0, malformed = 0, answered = 0, timeouts = 0, late = 0;
    std::uint32_t newest_ack = 0;
    double max_force = 0.0;
    std::vector<double> rtt_us;
    rtt_us.reserve(t.samples.size());
    const auto period = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / rate));
    auto next = std::chrono::steady_clock::now();
    std::vector<std::chrono::steady_clock::time_point> sent_at(t.samples.size());

    // Handles one received datagram; returns its ack when it is a force packet.
    const auto take = [&](std::size_t n) -> std::optional<std::uint32_t> {
        if (n > buffer.size()) {
            ++malformed;
            return std::nullopt;
        }
        const std::optional<Packet> p = decode_packet(std::span(buffer.data(), n));
        if (!p || p->type() != PacketType::Force) {
            ++malformed;
            return std::nullopt;
        }
        const auto& f = std::get<ForcePacket>(p->body);
        ++forces;
        max_force = std::max(max_force, length(f.force));
        if (f.ack == 0 || f.ack > t.samples.size()) {
            ++malformed;
            return std::nullopt;
        }
        if (static_cast<std::int32_t>(f.ack - newest_ack) > 0) {
            newest_ack = f.ack;
            ++answered;
            rtt_us.push_back(std::chrono::duration<double, std::micro>(
                                 std::chrono::steady_clock::now() - sent_at[f.ack - 1])
                                 .count());
            if (log) {
                const TrajectorySample& s = t.samples[f.ack - 1];
                log << f.ack << ',' << s.position.x << ',' << s.position.y << ',' << s.position.z
                    << ',' << s.buttons << ',' << f.flags << ',' << f.force.x << ',' << f.force.y
                    << ',' << f.force.z << '\n';
            }
        } else {
            ++late;  // a repeat for a pose already answered (the loop sends every tick)
        }
        return f.ack;
    };

    for (std::size_t i = 0; i < t.samples.size(); ++i) {
        std::this_thread::sleep_until(next);
        next += period;
        const auto seq = static_cast<std::uint32_t>(i + 1);
        sent_at[i] = std::chrono::steady_clock::now();
        socket.send_to(
            encode_packet({seq, PosePacket{t.samples[i].position, t.samples[i].buttons}}), to);
        if (lockstep) {
            const auto give_up = sent_at[i] + std::chrono::microseconds(
                                                  static_cast<std::int64_t>(timeout_ms * 1000.0));
            bool got = false;
            while (!got && std::chrono::steady_clock::now() < give_up) {
                if (const auto n = socket.receive(buffer, nullptr, 1)) {
                    const std::optional<std::uint32_t> ack = take(*n);
                    got = ack && static_cast<std::int32_t>(*ack - seq) >= 0;
                }
            }
            if (!got) ++timeouts;
            next = std::max(next, std::chrono::steady_clock::now());
        } else {
            while (const auto n = socket.receive(buffer, nullptr, 0))
                take(*n);
        }
    }
    // Collect the stragglers, then say goodbye (a few times: UDP may drop one).
    const auto drain_until = std::chrono::steady_clock::now() + std::chrono::milliseconds(50);
    while (std::chrono::steady_clock::now() < drain_until) {
        if (const auto n = socket.receive(buffer, nullptr, 5)) take(*n);
    }
    for (std::uint32_t k = 0; k < 3; ++k) {
        socket.send_to(
            encode_packet({static_cast<std::uint32_t>(t.samples.size() + 1 + k), ByePacket{}}), to);
    }
    std::sort(rtt_us.begin(), rtt_us.end());
    const auto pct = [&](double q) {
        if (rtt_us.empty()) return 0.0;
        const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(rtt_us.size())));
        return rtt_us[std::min(rtt_us.size(), std::max<std::size_t>(k, 1)) - 1];
    };
    std::cout << "{\"sent\": " << t.samples.size() << ", \"answered\": " << answered
              << ", \"forces_received\": " << forces << ", \"repeats\": " << late
              << ", \"malformed\": " << malformed << ", \"timeouts\": " << timeouts
              << ", \"max_force\": " << max_force << ", \"rtt_p50_us\": " << pct(0.5)
              << ", \"rtt_p99_us\": " << pct(0.99)
              << ", \"lockstep\": " << (lockstep ? "true" : "false") << "}\n";
    if (lockstep) return answered == t.samples.size() ? 0 : 1;
    return forces > 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Options o = parse(argc, argv);
        if (o.positionals.empty()) throw UsageError("no command");
        if (o.positionals[0] == "play") return play(o);
        if (o.positionals[0] == "synth") return synth(o);
        throw UsageError("unknown command '" + o.positionals[0] + "'");
    } catch (const UsageError& e) {
        std::cerr << "sandtin-haptic-replay: error: " << e.what() << "\n" << kUsage;
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "sandtin-haptic-replay: error: " << e.what() << "\n";
        return 1;
    }
}
