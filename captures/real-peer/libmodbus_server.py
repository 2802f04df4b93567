#!/usr/bin/python3
"""A Modbus RTU server played by Debian's libmodbus (libmodbus5, through ctypes): the
server of the library's own test programs, modbus_receive and modbus_reply on a serial device,
with 2100 holding registers, 16 coils, 16 inputs and 16 input registers, all 0 at the start.
Writes {"station": STATION} to READY_JSON when it serves.

usage: libmodbus_server.py DEVICE STATION READY_JSON
"""
import ctypes
import json
import sys

VOID = ctypes.c_void_p


def library():
    lib = ctypes.CDLL("libmodbus.so.5")
    lib.modbus_new_rtu.restype = VOID
    lib.modbus_new_rtu.argtypes = [ctypes.c_char_p, ctypes.c_int, ctypes.c_char, ctypes.c_int,
                                   ctypes.c_int]
    lib.modbus_set_slave.argtypes = [VOID, ctypes.c_int]
    lib.modbus_connect.argtypes = [VOID]
    lib.modbus_mapping_new.restype = VOID
    lib.modbus_mapping_new.argtypes = [ctypes.c_int] * 4
    lib.modbus_receive.argtypes = [VOID, VOID]
    lib.modbus_reply.argtypes = [VOID, VOID, ctypes.c_int, VOID]
    return lib


def main():
    device, station, ready = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    lib = library()
    ctx = lib.modbus_new_rtu(device.encode(), 9600, b"N", 8, 1)
    lib.modbus_set_slave(ctx, station)
    if lib.modbus_connect(ctx) != 0:
        sys.exit(f"libmodbus_server: cannot open {device}")
    mapping = lib.modbus_mapping_new(16, 16, 2100, 16)
    request = ctypes.create_string_buffer(260)  # MODBUS_RTU_MAX_ADU_LENGTH
    with open(ready, "w", encoding="utf-8") as f:
        json.dump({"station": station}, f)
    while True:
        length = lib.modbus_receive(ctx, request)
        if length > 0:
            lib.modbus_reply(ctx, request, length, mapping)


if __name__ == "__main__":
    main()
