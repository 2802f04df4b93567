#!/usr/bin/python3
"""A Modbus RTU master played by Debian's libmodbus (libmodbus5, through ctypes), running the
exchanges of a library test suite against one server: report server ID (0x11), read/write
multiple registers (0x17), write single register (0x06), write multiple registers (0x10),
write single coil (0x05) and read holding registers (0x03). Prints, as JSON, what each call
returned and the server ID's text.

usage: libmodbus_master.py DEVICE STATION
"""
import ctypes
import json
import sys

VOID = ctypes.c_void_p
INT = ctypes.c_int


def library():
    lib = ctypes.CDLL("libmodbus.so.5")
    lib.modbus_new_rtu.restype = VOID
    lib.modbus_new_rtu.argtypes = [ctypes.c_char_p, INT, ctypes.c_char, INT, INT]
    for name, args in {"modbus_set_slave": [VOID, INT], "modbus_connect": [VOID],
                       "modbus_report_slave_id": [VOID, INT, VOID],
                       "modbus_write_and_read_registers": [VOID, INT, INT, VOID, INT, INT, VOID],
                       "modbus_write_register": [VOID, INT, ctypes.c_uint16],
                       "modbus_write_registers": [VOID, INT, INT, VOID],
                       "modbus_write_bit": [VOID, INT, INT],
                       "modbus_read_registers": [VOID, INT, INT, VOID]}.items():
        getattr(lib, name).argtypes = args
    return lib


def main():
    device, station = sys.argv[1], int(sys.argv[2])
    lib = library()
    ctx = lib.modbus_new_rtu(device.encode(), 9600, b"N", 8, 1)
    lib.modbus_set_slave(ctx, station)
    if lib.modbus_connect(ctx) != 0:
        sys.exit(f"libmodbus_master: cannot open {device}")
    ident = (ctypes.c_uint8 * 256)()
    words = (ctypes.c_uint16 * 125)()
    written = (ctypes.c_uint16 * 3)(500, 501, 502)
    calls = [
        ("report_server_id", 0x11, lib.modbus_report_slave_id(ctx, 256, ident)),
        ("write_and_read_registers", 0x17,
         lib.modbus_write_and_read_registers(ctx, 1250, 2, written, 1050, 4, words)),
        ("write_register", 0x06, lib.modbus_write_register(ctx, 1251, 1)),
        ("write_registers", 0x10, lib.modbus_write_registers(ctx, 1500, 3, written)),
        ("write_bit", 0x05, lib.modbus_write_bit(ctx, 0, 1)),
        ("read_registers", 0x03, lib.modbus_read_registers(ctx, 1030, 4, words)),
    ]
    length = calls[0][2]
    # Server ID byte, run indicator, then the server's text.
    text = bytes(ident[2:length]).decode("ascii", "replace") if length > 2 else ""
    print(json.dumps({"station": station, "server_id_text": text,
                      "exchanges": [{"call": c, "function": f, "returned": r}
                                    for c, f, r in calls]}))


if __name__ == "__main__":
    main()
