// modbus_peer: an independent Modbus server for DriftLab's device tests and benchmark,
// built on libmodbus only (none of DriftLab's own code). It serves holding and input
// registers over TCP (any number of clients, select loop) or RTU (a serial device, e.g.
// one end of a socat pseudo-terminal pair) and misbehaves on command, so tests can
// exercise a module that stalls, drops the connection or answers with exceptions.
//
// Usage:
//   modbus_peer --tcp PORT [--unit N] [options]     (PORT 0 = any free port)
//   modbus_peer --rtu DEVICE [--baud N] [--unit N] [options]
// Options:
//   --input ADDR=VALUE     initial input register (0-based address; repeatable)
//   --holding ADDR=VALUE   initial holding register (repeatable)
//   --clock ADDR           input registers ADDR, ADDR+1 hold CLOCK_MONOTONIC in ms
//                          (high word first), refreshed when a request arrives
//   --log-writes           print every accepted write of holding registers (functions 6
//                          and 16) on standard output: "write MS ADDR V1 [V2 ...]", MS being
//                          CLOCK_MONOTONIC in milliseconds, V the register contents after it
// Standard input, one command per line:
//   set input|holding ADDR VALUE    stall    resume    drop    exception CODE    normal    quit
// Standard output: "ready PORT" once listening (TCP) or "ready rtu" (RTU), then one line per
// command acknowledged ("ok ...") so a test can wait for it.

#include <modbus/modbus.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <unistd.h>

namespace {

enum class Mode { Normal, Stall, Exception };

struct Peer {
    modbus_t *ctx = nullptr;
    modbus_mapping_t *map = nullptr;
    Mode mode = Mode::Normal;
    int exceptionCode = MODBUS_EXCEPTION_SLAVE_OR_SERVER_FAILURE;
    int clockAddress = -1;
    bool logWrites = false;
    bool quit = false;
};

[[noreturn]] void die(const char *what)
{
    std::fprintf(stderr, "modbus_peer: %s: %s\n", what, modbus_strerror(errno));
    std::exit(1);
}

bool parseAssignment(const char *text, int &address, int &value)
{
    return std::sscanf(text, "%d=%d", &address, &value) == 2 && address >= 0 && address < 10000 && value >= 0 &&
           value <= 65535;
}

void refreshClock(Peer &p)
{
    if (p.clockAddress < 0)
        return;
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    const unsigned long long ms = static_cast<unsigned long long>(ts.tv_sec) * 1000ULL + ts.tv_nsec / 1000000;
    const unsigned v = static_cast<unsigned>(ms & 0xffffffffULL);
    p.map->tab_input_registers[p.clockAddress] = static_cast<uint16_t>(v >> 16);
    p.map->tab_input_registers[p.clockAddress + 1] = static_cast<uint16_t>(v & 0xffff);
}

void logWrite(const Peer &p, const uint8_t *query)
{
    const int h = modbus_get_header_length(p.ctx);
    const int function = query[h];
    if (function != 0x06 && function != 0x10)
        return;
    const int address = (query[h + 1] << 8) | query[h + 2];
    const int count = function == 0x06 ? 1 : ((query[h + 3] << 8) | query[h + 4]);
    if (address < 0 || count < 1 || address + count > 10000)
        return;
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    std::printf("write %lld %d", static_cast<long long>(ts.tv_sec) * 1000LL + ts.tv_nsec / 1000000, address);
    for (int i = 0; i < count; ++i)
        std::printf(" %u", static_cast<unsigned>(p.map->tab_registers[address + i]));
    std::printf("\n");
    std::fflush(stdout);
}

// Handles one request on the current socket / serial line. Returns false if the peer
// closed the connection.
bool serve(Peer &p)
{
    uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
    const int rc = modbus_receive(p.ctx, query);
    if (rc == 0)
        return true; // RTU: request for another unit, ignored
    if (rc < 0)
        return false;
    switch (p.mode) {
    case Mode::Stall: return true; // read and never answer
    case Mode::Exception: modbus_reply_exception(p.ctx, query, static_cast<unsigned>(p.exceptionCode)); return true;
    case Mode::Normal:
        refreshClock(p);
        if (modbus_reply(p.ctx, query, rc, p.map) >= 0 && p.logWrites)
            logWrite(p, query);
        return true;
    }
    return true;
}

void ack(const std::string &what)
{
    std::printf("ok %s\n", what.c_str());
    std::fflush(stdout);
}

// Returns true when the command asks to drop every connection.
bool command(Peer &p, const std::string &line)
{
    char area[16] = {0};
    int address = 0, value = 0;
    if (std::sscanf(line.c_str(), "set %15s %d %d", area, &address, &value) == 3 && address >= 0 &&
        address < 10000 && value >= 0 && value <= 65535) {
        if (std::strcmp(area, "input") == 0)
            p.map->tab_input_registers[address] = static_cast<uint16_t>(value);
        else
            p.map->tab_registers[address] = static_cast<uint16_t>(value);
        ack(line);
    } else if (line == "stall") {
        p.mode = Mode::Stall;
        ack(line);
    } else if (line == "resume" || line == "normal") {
        p.mode = Mode::Normal;
        ack(line);
    } else if (std::sscanf(line.c_str(), "exception %d", &value) == 1) {
        p.mode = Mode::Exception;
        p.exceptionCode = value;
        ack(line);
    } else if (line == "drop") {
        ack(line);
        return true;
    } else if (line == "quit") {
        p.quit = true;
        ack(line);
    } else if (!line.empty()) {
        std::fprintf(stderr, "modbus_peer: unknown command '%s'\n", line.c_str());
    }
    return false;
}

// Reads whole lines from standard input; returns false at end of input.
bool readCommands(Peer &p, std::string &buffer, bool &drop)
{
    char chunk[512];
    const ssize_t n = read(STDIN_FILENO, chunk, sizeof chunk);
    if (n <= 0)
        return false;
    buffer.append(chunk, static_cast<size_t>(n));
    size_t eol;
    while ((eol = buffer.find('\n')) != std::string::npos) {
        std::string line = buffer.substr(0, eol);
        buffer.erase(0, eol + 1);
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        drop = command(p, line) || drop;
    }
    return true;
}

// Waits until a descriptor in `set` (the highest `top`) is readable; false when a signal
// interrupted the wait (the caller checks quit and waits again).
bool waitReadable(fd_set &set, int top)
{
    if (select(top + 1, &set, nullptr, nullptr, nullptr) < 0) {
        if (errno == EINTR)
            return false;
        die("select");
    }
    return true;
}

// Reads the test's commands when standard input is readable; true when one asked to drop the
// connections. stdinOpen turns false at the end of standard input.
bool commandsAskDrop(Peer &p, fd_set &set, bool &stdinOpen, std::string &buffer)
{
    if (!stdinOpen || !FD_ISSET(STDIN_FILENO, &set))
        return false;
    bool drop = false;
    stdinOpen = readCommands(p, buffer, drop);
    return drop;
}

int runTcp(Peer &p, int port)
{
    const int server = modbus_tcp_listen(p.ctx, 16);
    if (server < 0)
        die("listen");
    sockaddr_in addr{};
    socklen_t len = sizeof addr;
    getsockname(server, reinterpret_cast<sockaddr *>(&addr), &len);
    std::printf("ready %d\n", port == 0 ? ntohs(addr.sin_port) : port);
    std::fflush(stdout);
    std::vector<int> clients;
    std::string buffer;
    bool stdinOpen = true;
    while (!p.quit) {
        fd_set set;
        FD_ZERO(&set);
        FD_SET(server, &set);
        int top = server;
        if (stdinOpen) {
            FD_SET(STDIN_FILENO, &set);
            top = std::max(top, STDIN_FILENO);
        }
        for (int c : clients) {
            FD_SET(c, &set);
            top = std::max(top, c);
        }
        if (!waitReadable(set, top))
            continue;
        if (commandsAskDrop(p, set, stdinOpen, buffer)) {
            for (int c : clients)
                close(c);
            clients.clear();
            continue;
        }
        if (FD_ISSET(server, &set)) {
            const int c = accept(server, nullptr, nullptr);
            if (c >= 0)
                clients.push_back(c);
        }
        for (size_t i = 0; i < clients.size();) {
            if (!FD_ISSET(clients[i], &set)) {
                ++i;
                continue;
            }
            modbus_set_socket(p.ctx, clients[i]);
            if (serve(p)) {
                ++i;
            } else {
                close(clients[i]);
                clients.erase(clients.begin() + static_cast<long>(i));
            }
        }
    }
    for (int c : clients)
        close(c);
    close(server);
    return 0;
}

int runRtu(Peer &p)
{
    if (modbus_connect(p.ctx) < 0)
        die("open serial device");
    std::printf("ready rtu\n");
    std::fflush(stdout);
    std::string buffer;
    bool stdinOpen = true;
    const int fd = modbus_get_socket(p.ctx);
    while (!p.quit) {
        fd_set set;
        FD_ZERO(&set);
        FD_SET(fd, &set);
        if (stdinOpen)
            FD_SET(STDIN_FILENO, &set);
        if (!waitReadable(set, std::max(fd, STDIN_FILENO)))
            continue;
        if (commandsAskDrop(p, set, stdinOpen, buffer))
            modbus_flush(p.ctx);
        if (FD_ISSET(fd, &set))
            serve(p); // a bad frame (CRC) is answered by nothing, as a real module does
    }
    modbus_close(p.ctx);
    return 0;
}

} // namespace

int main(int argc, char **argv)
{
    Peer p;
    int port = -1, baud = 19200, unit = 1;
    const char *device = nullptr;
    std::vector<std::pair<int, int>> inputs, holdings;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const char *next = i + 1 < argc ? argv[i + 1] : nullptr;
        int address = 0, value = 0;
        if (a == "--tcp" && next) {
            port = std::atoi(argv[++i]);
        } else if (a == "--rtu" && next) {
            device = argv[++i];
        } else if (a == "--baud" && next) {
            baud = std::atoi(argv[++i]);
        } else if (a == "--unit" && next) {
            unit = std::atoi(argv[++i]);
        } else if (a == "--log-writes") {
            p.logWrites = true;
        } else if (a == "--clock" && next) {
            p.clockAddress = std::atoi(argv[++i]);
        } else if ((a == "--input" || a == "--holding") && next && parseAssignment(next, address, value)) {
            (a == "--input" ? inputs : holdings).push_back({address, value});
            ++i;
        } else {
            std::fprintf(stderr, "modbus_peer: bad argument '%s' (see the comment at the top of modbus_peer.cpp)\n", a.c_str());
            return 2;
        }
    }
    if ((port < 0) == (device == nullptr)) {
        std::fprintf(stderr, "modbus_peer: give --tcp PORT or --rtu DEVICE\n");
        return 2;
    }
    p.ctx = device ? modbus_new_rtu(device, baud, 'N', 8, 1) : modbus_new_tcp("127.0.0.1", port);
    if (!p.ctx)
        die("context");
    modbus_set_slave(p.ctx, unit);
    p.map = modbus_mapping_new(0, 0, 10000, 10000);
    if (!p.map)
        die("mapping");
    if (p.clockAddress < 0 || p.clockAddress > 9998)
        p.clockAddress = -1;
    for (auto [a, v] : inputs)
        p.map->tab_input_registers[a] = static_cast<uint16_t>(v);
    for (auto [a, v] : holdings)
        p.map->tab_registers[a] = static_cast<uint16_t>(v);
    const int rc = device ? runRtu(p) : runTcp(p, port);
    modbus_mapping_free(p.map);
    modbus_free(p.ctx);
    return rc;
}
