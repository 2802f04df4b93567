#!/usr/bin/python3
"""A GSL inverter played by pymodbus (Debian's python3-pymodbus: 3.0 on Debian 12, 3.8 on 13,
3.15 on testing): a Modbus RTU server on a serial device holding GSL register IDs at their
decimal wire addresses (ID 1050 = 0x041A). Writes the words it holds as JSON before it starts
serving, for the ground truth.

usage: gsl_server.py DEVICE STATION TRUTH_JSON
"""
import json
import sys

from pymodbus.datastore import ModbusSequentialDataBlock, ModbusServerContext
from pymodbus.server import StartSerialServer

# The names of pymodbus's API changed between the releases Debian ships.
try:  # 3.0
    from pymodbus.transaction import ModbusRtuFramer as RTU_FRAMER
except ImportError:  # 3.7 and later
    from pymodbus import FramerType
    RTU_FRAMER = FramerType.RTU
try:  # up to 3.9
    from pymodbus.datastore import ModbusSlaveContext as DeviceContext
    DEVICES_KEYWORD = "slaves"
except ImportError:  # 3.10 and later
    from pymodbus.datastore import ModbusDeviceContext as DeviceContext
    DEVICES_KEYWORD = "devices"


def text_words(text):
    padded = text.ljust(10)
    return [ord(padded[i]) << 8 | ord(padded[i + 1]) for i in range(0, 10, 2)]


def gsl_registers():
    """ID -> word: a 3-phase plant at noon, model and maker names, one alarm bit."""
    held = {}
    for i, w in enumerate(text_words("GSL000500K") + text_words("KSTARSOLAR")):
        held[1000 + i] = w
    held.update({1030: 0x0004, 1031: 0, 1032: 0, 1033: 0x0830})
    measured = [4012, 4008, 4021, 712, 709, 715, 5001, 99, 98, 99, 162, 160, 163, 3, 2, 4,
                6120, 84, 51, 187, 968, 42, 413, 2024, 6, 21, 6, 12, 30, 2024, 6, 20, 19, 45,
                3, 75, 3, 52910, 485, 9, 525, 0, 100, 99, 1, 4431]
    for i, w in enumerate(measured):
        held[1050 + i] = w
    return held


def holding_registers(words):
    """A device whose request address a reads words[a]."""
    try:
        # 3.0: zero_mode makes the request's address the block index (no +1 of Modbus
        # references).
        return DeviceContext(hr=ModbusSequentialDataBlock(0, words), zero_mode=True)
    except TypeError:
        # Later releases always add 1 to the request's address: the block starts at 1.
        return DeviceContext(hr=ModbusSequentialDataBlock(1, words))


def main():
    device, station, truth_path = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    held = gsl_registers()
    words = [0] * 2100
    for address, value in held.items():
        words[address] = value
    context = ModbusServerContext(**{DEVICES_KEYWORD: {station: holding_registers(words)}},
                                  single=False)
    with open(truth_path, "w", encoding="utf-8") as f:
        json.dump({"station": station, "holding_registers":
                   {str(a): v for a, v in sorted(held.items())}}, f, indent=1)
    StartSerialServer(context=context, framer=RTU_FRAMER, port=device, baudrate=9600,
                      bytesize=8, parity="N", stopbits=1)


if __name__ == "__main__":
    main()
