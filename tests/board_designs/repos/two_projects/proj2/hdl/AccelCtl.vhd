-- AccelCtl.vhd: an accelerometer controller's interface (clean-room, written for botsim's
-- tests): after reset it reports, once a 16-clock measurement is done, an X reading that
-- depends on the system clock it is told (SYSCLK_FREQUENCY_HZ / 1 MHz), with Data_Ready.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity AccelCtl is
  generic (
    SYSCLK_FREQUENCY_HZ : integer := 50000000
  );
  port (
    SYSCLK     : in  std_logic;
    RESET      : in  std_logic;
    ACCEL_X    : out std_logic_vector(11 downto 0);
    Data_Ready : out std_logic
  );
end AccelCtl;

architecture behavioral of AccelCtl is
  signal count : unsigned(3 downto 0) := (others => '0');
  signal x     : std_logic_vector(11 downto 0) := (others => '0');
  signal ready : std_logic := '0';
begin
  process (SYSCLK)
  begin
    if rising_edge(SYSCLK) then
      if RESET = '1' then
        count <= (others => '0');
        ready <= '0';
      elsif count = 15 then
        x <= std_logic_vector(to_unsigned(SYSCLK_FREQUENCY_HZ / 1000000, 12));
        ready <= '1';
      else
        count <= count + 1;
      end if;
    end if;
  end process;
  ACCEL_X <= x;
  Data_Ready <= ready;
end behavioral;
